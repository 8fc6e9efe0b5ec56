# The panel's coverage, density and size factor as nimbus overrides (--set keys), from the preset's own keys.

# Noise frequencies (cycles per metre): divided by the size factor.
FREQUENCY_KEYS = ("frequency", "erosion_frequency", "cauliflower_frequency",
                  "displacement_frequency", "furrow_frequency")
# Lengths (metres): multiplied by the size factor.
LENGTH_KEYS = ("displacement", "base_softness", "ceiling_softness", "flat_layer", "temperature_height")
# Below this an altitude means "none" (stretch_altitude -1e30: fibres everywhere).
NO_ALTITUDE = 1e29


def base_centre(cloud):
    """The cloud's base centre: below the centre of its lowest shape (a field's: the field's centre),
    at base_altitude (else at that shape's bottom)."""
    lowest = None
    for s in cloud.get("shapes", []) or []:
        c, r = s.get("center"), s.get("size")
        if not c or not r:
            continue
        points = [c] + ([s["end"]] if "end" in s else [])
        bottom = min(p[2] for p in points) - r[2]
        if lowest is None or bottom < lowest[2]:
            lowest = (float(c[0]), float(c[1]), bottom)
    x, y, z = lowest if lowest else (0.0, 0.0, 0.0)
    field = cloud.get("field")
    if isinstance(field, dict) and "center" in field:
        x, y = float(field["center"][0]), float(field["center"][1])
    if "base_altitude" in cloud:
        z = float(cloud["base_altitude"])
    return (x, y, z)


def _about(point, centre, f):
    return [c + f * (p - c) for p, c in zip(point, centre)]


def size_overrides(cloud, f):
    """Overrides that scale the cloud by f about its base centre (only keys the preset has)."""
    if f == 1.0:
        return {}
    out = {}
    base = base_centre(cloud)
    for i, s in enumerate(cloud.get("shapes", []) or []):
        if "size" in s:
            out[f"shapes.{i}.size"] = [v * f for v in s["size"]]
        for key in ("center", "end"):
            if key in s:
                out[f"shapes.{i}.{key}"] = _about(s[key], base, f)
    for key in FREQUENCY_KEYS:
        if key in cloud:
            out[key] = cloud[key] / f
    for key in LENGTH_KEYS:
        if key in cloud:
            out[key] = cloud[key] * f
    for key in ("stretch_altitude", "ceiling_altitude"):
        alt = cloud.get(key)
        if isinstance(alt, (int, float)) and abs(alt) < NO_ALTITUDE:
            out[key] = base[2] + f * (alt - base[2])
    field = cloud.get("field")
    if isinstance(field, dict):
        if "size" in field:
            out["field.size"] = [v * f for v in field["size"]]
        if "center" in field:
            out["field.center"] = _about(field["center"], base[:2], f)
        for key in ("min_diameter", "max_diameter"):
            if key in field:
                out[f"field.{key}"] = field[key] * f
    return out


def build(preset_doc, params):
    """All overrides for params (coverage, density, size) against the preset document."""
    cloud = preset_doc.get("cloud", {})
    out = {}
    for key in ("coverage", "density"):
        value = getattr(params, key)
        if value is not None and key in cloud and value != cloud[key]:
            out[key] = float(value)
    out.update(size_overrides(cloud, float(params.size)))
    return out


def voxel_size(preset_doc, params):
    """The voxel size to generate at: the panel's, else the preset's times the size factor (None: the preset's)."""
    if params.voxel_size > 0:
        return float(params.voxel_size)
    if params.size == 1.0 or not preset_doc.get("voxel_size"):
        return None  # the preset's own
    return float(preset_doc["voxel_size"]) * float(params.size)
