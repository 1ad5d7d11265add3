"""The one-line render status Blender shows: in the status bar for F12, in the viewport header when
the viewport renders. No bpy: the viewport's render thread builds it too."""

from __future__ import annotations


def stats_line(renderer, pass_index: int, done: int, target: int | None, seconds: float, warnings,
               tile=(0, 1), quote_warning: bool = True) -> str:
    """``Prism | Pass 3 | 12/64 spp | 1.30 M rays/s | <strategy> | ...`` (``12 spp`` when ``target`` is
    None: a viewport rendering until stopped); ``Prism | Tile 2/9 | ...`` when ``tile`` (index, count)
    is one of several, and how adaptive sampling and the time limit stand. ``quote_warning``: the first
    warning's text too (the viewport header, where nothing else shows it); F12 and batch renders report
    each warning once by itself, and their line (printed every pass) only counts them."""
    stats = renderer.stats
    rays_per_second = stats.get("rays_cast", 0) / seconds if seconds > 0 else 0.0
    head = f"Prism | Tile {tile[0] + 1}/{tile[1]}" if tile[1] > 1 else "Prism"
    parts = [
        f"{head} | Pass {pass_index} | {done}/{target} spp" if target else f"{head} | Pass {pass_index} | {done} spp",
        f"{rays_per_second / 1e6:.2f} M rays/s",
    ]
    if renderer.settings.adaptive_threshold > 0:
        x0, y0, x1, y1 = renderer.region
        parts.append("converged" if renderer.converged else
                     f"{renderer.active_pixels / max(1, (x1 - x0) * (y1 - y0)):.0%} of pixels sampling")
    if renderer.time_up:
        parts.append("time limit reached")
    parts.append(renderer.strategy)
    if stats.get("nan_samples"):
        parts.append(f"{stats['nan_samples']} NaN samples dropped")
    notes = list(warnings) + list(stats.get("warnings") or [])
    if notes:
        parts.append(f"{len(notes)} warning(s): {notes[0]}" if quote_warning else f"{len(notes)} warning(s)")
    return " | ".join(parts)


def timecode(seconds: float) -> str:
    """Elapsed time as Blender prints it: ``00:07.25`` (minutes, seconds, hundredths), ``01:02:07.25`` past an hour."""
    hundredths = int(round(max(seconds, 0.0) * 100))
    minutes, hundredths = divmod(hundredths, 6000)
    hours, minutes = divmod(minutes, 60)
    clock = f"{minutes:02d}:{hundredths // 100:02d}.{hundredths % 100:02d}"
    return f"{hours:02d}:{clock}" if hours else clock
