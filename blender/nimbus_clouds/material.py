# The cloud material with nimbus's optics, as the library gives them (the plan's "optics":
# nimbus.plan, nimbus generate --plan-json): extinction per unit density, albedo, dual-lobe HG phase.
#
# sigma_t = extinction x density; one Volume Scatter node, sigma_s = albedo x sigma_t, whose HG
# anisotropy is g_f at a random share w of points and g_b at the rest (White Noise of the shading
# point: a new lobe for every scattering event, so the phase is the w/(1 - w) mixture in
# expectation); Volume Absorption, sigma_a = (1 - albedo) x sigma_t. Two Volume Scatter nodes (or
# Principled Volume, one lobe) cannot hold the mixture: Cycles 3.4 sums the phase functions of
# several scatter closures without their weights (docs/blender.md, measured).
import bpy

# Node names (stable: the panel and the tests find the nodes by them).
N_DENSITY = "nimbus density"
N_EXTINCTION = "nimbus extinction"
N_ALBEDO = "nimbus albedo"
N_WEIGHT = "nimbus forward weight"
N_G_FORWARD = "nimbus forward g"
N_G_BACKWARD = "nimbus backward g"
N_SIGMA_T = "nimbus sigma_t"
N_POSITION = "nimbus position"
N_NOISE = "nimbus lobe noise"
N_IS_FORWARD = "nimbus lobe is forward"
N_G_SPREAD = "nimbus g_f - g_b"
N_G = "nimbus anisotropy"
N_SCATTER = "nimbus scatter"
N_ABSORPTION = "nimbus absorption"
N_ADD = "nimbus add"
N_OUTPUT = "nimbus output"


def _node(nodes, kind, name, location, label=None):
    n = nodes.new(kind)
    n.name = name
    n.label = label or name
    n.location = location
    return n


def _math(nodes, name, operation, location, b=None):
    n = _node(nodes, "ShaderNodeMath", name, location)
    n.operation = operation
    if b is not None:
        n.inputs[1].default_value = b
    return n


def build_tree(mat, optics):
    """Replaces mat's nodes with nimbus's optics (the plan's "optics" dict)."""
    extinction, albedo, phase = float(optics["extinction_per_m"]), float(optics["albedo"]), optics["phase"]
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    density = _node(nodes, "ShaderNodeAttribute", N_DENSITY, (-900, 200), "density (nimbus grid)")
    density.attribute_type = "GEOMETRY"
    density.attribute_name = "density"
    ext = _node(nodes, "ShaderNodeValue", N_EXTINCTION, (-900, 0), "extinction per unit density (1/m)")
    ext.outputs[0].default_value = extinction
    alb = _node(nodes, "ShaderNodeValue", N_ALBEDO, (-900, -350), "albedo")
    alb.outputs[0].default_value = albedo
    weight = _node(nodes, "ShaderNodeValue", N_WEIGHT, (-900, -150), "forward lobe weight")
    weight.outputs[0].default_value = float(phase["forward_weight"])

    sigma_t = _math(nodes, N_SIGMA_T, "MULTIPLY", (-650, 150))
    links.new(density.outputs["Fac"], sigma_t.inputs[0])
    links.new(ext.outputs[0], sigma_t.inputs[1])

    # The lobe of this scattering event: forward where a white noise of the point is below the weight.
    position = _node(nodes, "ShaderNodeNewGeometry", N_POSITION, (-1150, -550), "position")
    noise = _node(nodes, "ShaderNodeTexWhiteNoise", N_NOISE, (-900, -550), "lobe choice")
    noise.noise_dimensions = "3D"
    links.new(position.outputs["Position"], noise.inputs["Vector"])
    forward = _math(nodes, N_IS_FORWARD, "LESS_THAN", (-650, -400))
    links.new(noise.outputs["Value"], forward.inputs[0])
    links.new(weight.outputs[0], forward.inputs[1])
    g_f = _node(nodes, "ShaderNodeValue", N_G_FORWARD, (-900, -750), "forward lobe g")
    g_f.outputs[0].default_value = float(phase["g_forward"])
    g_b = _node(nodes, "ShaderNodeValue", N_G_BACKWARD, (-900, -900), "backward lobe g")
    g_b.outputs[0].default_value = float(phase["g_back"])
    spread = _math(nodes, N_G_SPREAD, "SUBTRACT", (-650, -800))
    links.new(g_f.outputs[0], spread.inputs[0])
    links.new(g_b.outputs[0], spread.inputs[1])
    g = _math(nodes, N_G, "MULTIPLY_ADD", (-400, -500))  # forward x (g_f - g_b) + g_b
    links.new(forward.outputs[0], g.inputs[0])
    links.new(spread.outputs[0], g.inputs[1])
    links.new(g_b.outputs[0], g.inputs[2])

    scatter = _node(nodes, "ShaderNodeVolumeScatter", N_SCATTER, (-150, 150))
    links.new(g.outputs[0], scatter.inputs["Anisotropy"])
    absorb = _node(nodes, "ShaderNodeVolumeAbsorption", N_ABSORPTION, (-150, -150))
    # Scatter: sigma_s = Color x Density; Absorption: sigma_a = (1 - Color) x Density (Cycles' closures).
    for n in (scatter, absorb):
        links.new(alb.outputs[0], n.inputs["Color"])
        links.new(sigma_t.outputs[0], n.inputs["Density"])

    add = _node(nodes, "ShaderNodeAddShader", N_ADD, (100, 0))
    links.new(scatter.outputs[0], add.inputs[0])
    links.new(absorb.outputs[0], add.inputs[1])
    out = _node(nodes, "ShaderNodeOutputMaterial", N_OUTPUT, (350, 0))
    links.new(add.outputs[0], out.inputs["Volume"])
    nodes.active = out
    return mat


def new_material(name, optics):
    mat = bpy.data.materials.new(name)
    build_tree(mat, optics)
    mat["nimbus_optics"] = 1  # marks the material as the add-on's
    return mat


def value_node(mat, name):
    """The material's node `name` when it is the add-on's tree, else None."""
    if mat is None or not mat.use_nodes or mat.node_tree is None:
        return None
    return mat.node_tree.nodes.get(name)


def assign(volume_data, mat):
    if volume_data.materials:
        volume_data.materials[0] = mat
    else:
        volume_data.materials.append(mat)
