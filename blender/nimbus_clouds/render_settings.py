# What Cycles needs to render a nimbus cloud as nimbus does, set on the scene when a cloud is added.
#
# - Volume bounces: Cycles' default of 0 is single scattering, and a cloud renders as dark grey
#   smoke. Measured on cumulus-humilis lit from the front (64x48, 64 spp, against 256 bounces):
#   0 bounces 21 % of the light, 4 74 %, 16 97.7 %, 32 100.0 % (docs/blender.md).
# - The denoiser: a Blender built without one (Debian's has no OpenImageDenoise) fails a render
#   that asks for denoising, which is Cycles' default; denoising is turned off there.
MIN_BOUNCES = 32


def _has_denoiser(cycles) -> bool:
    try:
        return bool(cycles.denoiser)  # "" where the enum has no item: no denoiser in this build
    except Exception:  # noqa: a Blender without the property has nothing to turn off
        return True


def ready_cycles(scene) -> list:
    """Raises the scene's Cycles bounces to MIN_BOUNCES and turns denoising off where this Blender
    has no denoiser. Returns what it changed, in words (empty: nothing)."""
    cycles = getattr(scene, "cycles", None)
    if cycles is None:
        return []
    changed = []
    if cycles.volume_bounces < MIN_BOUNCES:
        changed.append(f"Cycles volume bounces {cycles.volume_bounces} -> {MIN_BOUNCES}")
        cycles.volume_bounces = MIN_BOUNCES
    if cycles.max_bounces < MIN_BOUNCES:  # the total caps every kind of bounce
        changed.append(f"total bounces {cycles.max_bounces} -> {MIN_BOUNCES}")
        cycles.max_bounces = MIN_BOUNCES
    if cycles.use_denoising and not _has_denoiser(cycles):
        changed.append("render denoising off (this Blender has no denoiser)")
        cycles.use_denoising = False
    return changed
