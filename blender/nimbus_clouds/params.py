# One cloud's generation parameters, as plain Python (no bpy): what the panel and operator hold.
from dataclasses import dataclass
from typing import Optional


@dataclass
class CloudParams:
    preset: str
    seed: Optional[int] = None        # None: the preset's own
    voxel_size: float = 0.0           # metres; 0: the preset's (times the size factor)
    time: float = 0.0                 # seconds (still clouds; animated: the first frame's time)
    coverage: Optional[float] = None  # None: the preset's
    density: Optional[float] = None   # None: the preset's
    size: float = 1.0                 # size factor (nimbus generate --size)
    animated: bool = False
    frame_first: int = 1
    frame_last: int = 1
    fps: float = 24.0

    def frames(self):
        return range(self.frame_first, self.frame_last + 1) if self.animated else range(0)

    def start_frame(self):
        """nimbus's --start-frame: the frame at time 0, so frame_first is at `time` (whole frames)."""
        return self.frame_first - round(self.time * self.fps)

    def frame_time(self, frame):
        return (frame - self.start_frame()) / self.fps
