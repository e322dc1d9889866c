"""What the figures of condyn compare, condyn plot and condyn stress share (docs/plots.md): the
print style, log axes labelled at every decade that fits, titles wrapped to the figure's width,
and a layout that keeps every label inside the figure at the size the docs promise.

Imported by plot_compare.py, plot_result.py and plot_stress.py from this folder; matplotlib is
imported by the caller first (the Agg backend chosen), so a missing matplotlib is the caller's
exit 3.
"""
import math

import matplotlib
import matplotlib.ticker as mticker

# The widths the docs promise: across a page, and one column.
PAGE_WIDTH = 7.2
COLUMN_WIDTH = 3.5
# Space between a label and the figure's edge or the next label [figure fraction of an inch].
PAD_IN = 0.04


def literal(text):
    """Text matplotlib draws as written: a name like y$_1$ (legal in scenes) is not math."""
    return str(text).replace("$", r"\$")


def paper_style(plt):
    """8-9 pt text, thin lines: legible when the figure is printed at its own size. No tight
    bounding box on saving: a figure is written at the size it was made (7.2 or 3.5 in wide), and
    its layout (fit below) keeps every label inside it."""
    plt.rcParams.update({
        "font.size": 9, "axes.titlesize": 9, "axes.labelsize": 9, "xtick.labelsize": 8,
        "ytick.labelsize": 8, "legend.fontsize": 8, "legend.title_fontsize": 8,
        "lines.linewidth": 1.0, "lines.markersize": 3.5, "axes.linewidth": 0.6,
        "grid.linewidth": 0.4, "savefig.bbox": None,
    })


class DecadeLocator(mticker.Locator):
    """Ticks of a log axis at powers of ten: every decade when its labels fit along the axis (1.8
    label heights apart on a y axis, 4 label heights on an x axis), else every second, third, ...
    decade, the decades between them as minor ticks. matplotlib's own choice labelled two decades
    of seven on a 1.3 in tall panel. Below two decades in view it falls back to matplotlib's
    LogLocator, which labels 2 and 5 too."""

    def __init__(self, minor=False):
        super().__init__()
        self.minor = minor

    def __call__(self):
        vmin, vmax = self.axis.get_view_interval()
        return self.tick_values(vmin, vmax)

    def stride(self, lo, hi):
        axes = self.axis.axes
        vertical = self.axis is axes.yaxis
        extent = axes.bbox.height if vertical else axes.bbox.width
        length_pt = extent * 72.0 / axes.figure.dpi
        size = matplotlib.rcParams["ytick.labelsize" if vertical else "xtick.labelsize"]
        size = size if isinstance(size, (int, float)) else 8.0
        fit = max(1, int(length_pt / (size * (1.8 if vertical else 4.0))))
        return max(1, math.ceil((hi - lo) / fit))

    def tick_values(self, vmin, vmax):
        vmin, vmax = sorted((vmin, vmax))
        if not (vmax > 0 and math.isfinite(vmax)):
            return []
        vmin = vmin if vmin > 0 and math.isfinite(vmin) else vmax * 1e-10
        lo, hi = math.floor(math.log10(vmin)), math.ceil(math.log10(vmax))
        if hi - lo < 3:  # 1, 2 and 5 of each decade labelled, the rest minor
            subs = (3.0, 4.0, 6.0, 7.0, 8.0, 9.0) if self.minor else (1.0, 2.0, 5.0)
            return [m * 10.0 ** k for k in range(lo, hi + 1) for m in subs]
        stride = self.stride(lo, hi)
        start = math.floor(lo / stride) * stride
        majors = set(range(start, hi + stride + 1, stride))
        if not self.minor:
            return [10.0 ** k for k in sorted(majors)]
        if stride > 1:  # the decades between the labelled ones
            return [10.0 ** k for k in range(start, hi + 1) if k not in majors]
        if hi - lo > 8:  # 2..9 between decades would be a smear
            return []
        return [m * 10.0 ** k for k in range(lo, hi + 1) for m in range(2, 10)]


def log_axis(ax, which="y"):
    """A log scale on `which` with a label at every decade that fits (DecadeLocator)."""
    axis = ax.yaxis if which == "y" else ax.xaxis
    (ax.set_yscale if which == "y" else ax.set_xscale)("log")
    axis.set_major_locator(DecadeLocator())
    axis.set_minor_locator(DecadeLocator(minor=True))
    axis.set_minor_formatter(mticker.NullFormatter())
    axis.set_major_formatter(mticker.FuncFormatter(compact))


def compact(value, _position=None):
    """A log axis' label: 0.02, 5, 200 as written, 10^-6 or 2×10^-6 beyond (narrow)."""
    if 1e-3 <= value < 1e4:
        return f"{value:g}"
    exponent = math.floor(math.log10(value) + 1e-9)
    mantissa = round(value / 10.0 ** exponent)
    return (f"$10^{{{exponent}}}$" if mantissa == 1 else
            f"${mantissa}\\times10^{{{exponent}}}$")


def wrap(fig, text, fontsize, width_in):
    """`text` with line breaks so that no line is wider than width_in inches at fontsize (its own
    line breaks kept): a scene's name can be of any length."""
    from matplotlib.font_manager import FontProperties
    renderer = fig.canvas.get_renderer()
    props = FontProperties(size=fontsize)
    limit = width_in * fig.dpi

    def width(s):
        return renderer.get_text_width_height_descent(s.replace(r"\$", "$"), props, False)[0]

    lines = []
    for paragraph in text.split("\n"):
        line = ""
        for word in paragraph.split(" "):
            candidate = f"{line} {word}" if line else word
            if line and width(candidate) > limit:
                lines.append(line)
                line = word
            else:
                line = candidate
        lines.append(line)
    return "\n".join(lines)


def title(fig, text, fontsize=9):
    """A figure title, wrapped to the figure's width, at its top edge."""
    width = fig.get_figwidth() - 2 * PAD_IN
    return fig.suptitle(wrap(fig, text, fontsize, width), fontsize=fontsize,
                        y=1.0 - PAD_IN / fig.get_figheight(), va="top")


def legend_below(fig, handles, ncol, **kwargs):
    """A legend of the whole figure along its bottom edge, in as many rows as it needs: at most
    ncol columns, fewer where long names would run past the figure's edges (and a smaller font
    where even one column would)."""
    renderer = fig.canvas.get_renderer()
    room = (fig.get_figwidth() - 2 * PAD_IN) * fig.dpi
    size = matplotlib.rcParams["legend.fontsize"]
    while True:
        legend = fig.legend(handles=handles, loc="lower center", ncol=ncol, frameon=False,
                            bbox_to_anchor=(0.5, PAD_IN / fig.get_figheight()),
                            borderaxespad=0.0, fontsize=size, **kwargs)
        if legend.get_window_extent(renderer).width <= room or (ncol == 1 and size <= 5):
            return legend
        legend.remove()
        if ncol > 1:
            ncol -= 1
        else:
            size -= 0.5


def fit(fig, legend=None):
    """Lays the axes out inside the figure at its own size: between the title (tight_layout
    makes room for a suptitle) and a legend_below, every tick label and axis label inside."""
    bottom = 0.0
    if legend is not None:
        renderer = fig.canvas.get_renderer()
        bottom = (legend.get_window_extent(renderer).height / fig.dpi + 2 * PAD_IN) / \
            fig.get_figheight()
    # twice: the ticks of a log axis depend on its length (DecadeLocator), which the first
    # pass changes, and with them the room their labels take
    for _ in range(2):
        fig.tight_layout(rect=(0.0, bottom, 1.0, 1.0), pad=0.3, h_pad=0.6, w_pad=0.8)
