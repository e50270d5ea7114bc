"""Progress of a long operator: the window's progress bar in the UI, a line per stage in batch
(`blender -b`, scripts and the bpy module), where no window shows a bar."""

import time

import bpy


class Progress:
    def __init__(self, title, context=None):
        self.title = title
        self.window_manager = None if bpy.app.background or context is None else context.window_manager
        self.started = time.perf_counter()
        self.low, self.high = 0.0, 1.0
        if self.window_manager is not None:
            self.window_manager.progress_begin(0, 1000)

    def stage(self, name, low, high):
        """A stage that takes the share low..high of the whole; announced in batch."""
        self.low, self.high = low, high
        if self.window_manager is None:
            print(f"{self.title}: {name} ({time.perf_counter() - self.started:.1f} s)", flush=True)
        self.update(0.0)

    def update(self, share):
        """share of the current stage done (0..1)."""
        if self.window_manager is not None:
            whole = self.low + min(max(share, 0.0), 1.0) * (self.high - self.low)
            self.window_manager.progress_update(int(1000 * whole))

    def end(self):
        """Close the bar (or print the total); returns the seconds taken."""
        seconds = time.perf_counter() - self.started
        if self.window_manager is not None:
            self.window_manager.progress_end()
        else:
            print(f"{self.title}: done in {seconds:.1f} s", flush=True)
        return seconds
