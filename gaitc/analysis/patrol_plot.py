"""The picture of ``gaitc chances --plot``: the chance of completing at least k patrols
within the horizon against k, as bars (the best any controller can do) with the written or
given controller's chances as points; SVG written here, PNG through matplotlib when present."""

from __future__ import annotations

import html
from collections.abc import Sequence
from pathlib import Path

from gaitc.diagnostics import UsageError
from gaitc.diagnostics.files import write_atomically

WIDTH, HEIGHT = 640, 360
LEFT, RIGHT, TOP, BOTTOM = 60, 20, 40, 50


def patrol_svg(title: str, best: Sequence[float],
               others: Sequence[tuple[str, Sequence[float]]] = ()) -> str:
    """The SVG text: bars of ``best`` (k = 1, 2, ...), dots of each named series of
    ``others``, axes labelled in the robot's words."""
    k_max = len(best)
    plot_w, plot_h = WIDTH - LEFT - RIGHT, HEIGHT - TOP - BOTTOM
    slot = plot_w / max(k_max, 1)

    def y(p: float) -> float:
        return TOP + plot_h * (1.0 - min(1.0, max(0.0, p)))

    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" '
             f'viewBox="0 0 {WIDTH} {HEIGHT}" font-family="sans-serif" font-size="12">',
             f'<rect width="{WIDTH}" height="{HEIGHT}" fill="white"/>',
             f'<text x="{WIDTH / 2:.0f}" y="20" text-anchor="middle" font-size="14">'
             f'{html.escape(title)}</text>']
    for tick in (0.0, 0.25, 0.5, 0.75, 1.0):
        parts.append(f'<line x1="{LEFT}" y1="{y(tick):.1f}" x2="{WIDTH - RIGHT}" '
                     f'y2="{y(tick):.1f}" stroke="#ddd"/>')
        parts.append(f'<text x="{LEFT - 6}" y="{y(tick) + 4:.1f}" text-anchor="end">'
                     f'{tick:g}</text>')
    for k, p in enumerate(best, 1):
        x = LEFT + (k - 1) * slot
        parts.append(f'<rect x="{x + slot * 0.15:.1f}" y="{y(p):.1f}" width="{slot * 0.7:.1f}" '
                     f'height="{y(0.0) - y(p):.1f}" fill="#4c78a8"><title>at least {k}: '
                     f'{p:.6f}</title></rect>')
        parts.append(f'<text x="{x + slot / 2:.1f}" y="{HEIGHT - BOTTOM + 16}" '
                     f'text-anchor="middle">{k}</text>')
    colours = ("#e45756", "#54a24b", "#b279a2")
    for (name, series), colour in zip(others, colours, strict=False):
        for k, p in enumerate(series, 1):
            x = LEFT + (k - 0.5) * slot
            parts.append(f'<circle cx="{x:.1f}" cy="{y(p):.1f}" r="4" fill="{colour}">'
                         f'<title>{html.escape(name)}, at least {k}: {p:.6f}</title></circle>')
    legend = [("the best any controller can do", "#4c78a8")] + [
        (name, colour) for (name, _), colour in zip(others, colours, strict=False)]
    for i, (name, colour) in enumerate(legend):
        parts.append(f'<rect x="{LEFT + 10}" y="{TOP + 6 + 16 * i}" width="10" height="10" '
                     f'fill="{colour}"/><text x="{LEFT + 26}" y="{TOP + 15 + 16 * i}">'
                     f'{html.escape(name)}</text>')
    parts.append(f'<text x="{WIDTH / 2:.0f}" y="{HEIGHT - 10}" text-anchor="middle">'
                 'k, the patrols completed</text>')
    parts.append(f'<text x="16" y="{TOP + plot_h / 2:.0f}" text-anchor="middle" '
                 f'transform="rotate(-90 16 {TOP + plot_h / 2:.0f})">chance of at least k</text>')
    parts.append("</svg>")
    return "\n".join(parts) + "\n"


def write_patrol_plot(path: str | Path, title: str, best: Sequence[float],
                      others: Sequence[tuple[str, Sequence[float]]] = ()) -> None:
    """Write the plot to ``path``: ``.svg`` always, ``.png`` with matplotlib installed."""
    suffix = Path(path).suffix.lower()
    if suffix == ".svg":
        write_atomically(path, patrol_svg(title, best, others))
        return
    if suffix != ".png":
        raise UsageError(f"--plot writes .svg or .png, not '{suffix or path}'")
    try:
        # lazy: matplotlib is optional: PNG plots only
        import matplotlib

        matplotlib.use("Agg")
        # lazy: matplotlib is optional: PNG plots only
        from matplotlib import pyplot
    except ImportError:
        raise UsageError("a .png plot needs matplotlib (pip install matplotlib); "
                         "a .svg plot needs nothing") from None
    figure, axes = pyplot.subplots(figsize=(6.4, 3.6))
    ks = list(range(1, len(best) + 1))
    axes.bar(ks, best, color="#4c78a8", label="the best any controller can do")
    for name, series in others:
        axes.plot(ks, series, "o", label=name)
    axes.set_xlabel("k, the patrols completed")
    axes.set_ylabel("chance of at least k")
    axes.set_ylim(0, 1.05)
    axes.set_title(title)
    axes.legend(loc="lower left")
    figure.tight_layout()
    figure.savefig(str(path))
    pyplot.close(figure)
