"""An Embree device, and Embree's errors turned into ``EmbreeError`` messages."""

from __future__ import annotations

from . import library
from .errors import EmbreeError


class Device:
    """``rtcNewDevice`` / ``rtcReleaseDevice``; ``check(what)`` raises what Embree reports after a call."""

    def __init__(self, config: str = ""):
        self.library = library.load()
        self.handle = self.library.rtcNewDevice(config.encode() if config else None)
        if not self.handle:
            code = self.library.rtcGetDeviceError(None)
            raise EmbreeError(f"Embree could not create a device ({self._describe(code, None)})")

    def _describe(self, code: int, handle) -> str:
        name = (self.library.rtcGetErrorString(code) or b"").decode(errors="replace")
        detail = (self.library.rtcGetDeviceLastErrorMessage(handle) or b"").decode(errors="replace")
        return f"{name}: {detail}" if detail and detail != name else name or f"error {code}"

    def check(self, what: str) -> None:
        """Raise ``EmbreeError`` naming ``what`` if Embree recorded an error on this device since the last check."""
        code = self.library.rtcGetDeviceError(self.handle)
        if code:
            raise EmbreeError(f"Embree failed to {what} ({self._describe(code, self.handle)})")

    def release(self) -> None:
        if self.handle:
            self.library.rtcReleaseDevice(self.handle)
            self.handle = None

    def __del__(self):
        self.release()


_shared: list[Device] = []


def shared_device() -> Device:
    """The process's device: one thread pool and one set of CPU kernels for every scene Prism builds."""
    if not _shared:
        _shared.append(Device())
    return _shared[0]
