# The panel's coverage and density as nimbus overrides (--set keys), where they differ from the
# preset's own. The size factor is the library's (nimbus generate --size, nimbus.generate(size=)).


def build(preset_doc, params):
    """The overrides for params' coverage and density against the preset document."""
    cloud = preset_doc.get("cloud", {})
    out = {}
    for key in ("coverage", "density"):
        value = getattr(params, key)
        if value is not None and key in cloud and value != cloud[key]:
            out[key] = float(value)
    return out
