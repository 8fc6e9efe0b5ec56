# The nimbus Python module as the backend (nimbus.presets, preset, plan, generate, Volume.write).
import os


def import_module():
    """The nimbus module, or None when it does not import."""
    try:
        import nimbus  # noqa: the pybind11 module (build/python/nimbus)
    except ImportError:
        return None
    return nimbus if hasattr(nimbus, "generate") and hasattr(nimbus, "plan") else None


def _write_atomic(volume, path):
    """Volume.write to a temporary name beside path, then a rename: readers never see a partial file."""
    folder, name = os.path.split(path)
    tmp = os.path.join(folder, f".{name}.{os.getpid()}.partial.vdb")
    try:
        volume.write(tmp, half_float=True)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


class ModuleBackend:
    name = "module"

    def __init__(self, module):
        self.nimbus = module
        self._presets = {}

    def describe(self):
        return f"module {getattr(self.nimbus, '__file__', 'nimbus')}"

    def presets(self):
        return list(self.nimbus.presets())

    def preset(self, name):
        if name not in self._presets:
            self._presets[name] = self.nimbus.preset(name)
        return self._presets[name]

    def plan(self, preset, *, seed=None, voxel_size=None, res=None, time=0.0, overrides=None, size=1.0):
        return self.nimbus.plan(preset, seed=seed, voxel_size=voxel_size, res=res, time=time,
                                overrides=overrides or None, size=size)

    @staticmethod
    def _watch(progress, cancel, done, count):
        """nimbus.generate's progress callable: reports the whole job's fraction (`done` files of
        `count` before this one) and raises Cancelled when cancel is set, which stops the call."""
        from .generation import Cancelled

        def report(fraction):
            if cancel is not None and cancel.is_set():
                raise Cancelled("generation cancelled")
            if progress is not None:
                progress((done + fraction) / count)
        return report

    def generate_still(self, path, preset, *, seed, voxel_size, time, overrides, size=1.0, progress=None, cancel=None):
        volume = self.nimbus.generate(preset, seed=seed, voxel_size=voxel_size, time=time, overrides=overrides or None,
                                      size=size, progress=self._watch(progress, cancel, 0, 1))
        _write_atomic(volume, path)

    def generate_sequence(self, folder, pattern, preset, *, seed, voxel_size, overrides, first, last, fps, start_frame,
                          size=1.0, progress=None, cancel=None):
        """Writes folder/(pattern % frame) for frames first..last; frame n at time (n - start_frame) / fps."""
        count = last - first + 1
        for frame in range(first, last + 1):
            watch = self._watch(progress, cancel, frame - first, count)
            volume = self.nimbus.generate(preset, seed=seed, voxel_size=voxel_size,
                                          time=(frame - start_frame) / fps, overrides=overrides or None, size=size,
                                          progress=watch)
            _write_atomic(volume, os.path.join(folder, pattern % frame))
