"""The Baumgarte study's figure of `condyn compare` (docs/plots.md): error, drift and steps over
the grid of gains (alpha, beta), one heat map each, drawn by plot_compare.py."""
from compare_files import num

# The cell labels [pt]; smaller where a label would overflow its cell.
CELL_FONT = 6


def heat_map(plt, np, fig, ax, grid, labels, norm, cmap, bar_label, axes_values, default):
    cmap = plt.get_cmap(cmap).copy()
    cmap.set_bad("lightgray")  # failed or absent grid points
    cmap.set_under("white")  # exactly zero drift: below any log scale
    image = ax.imshow(np.ma.masked_invalid(grid), origin="lower", aspect="auto", cmap=cmap,
                      norm=norm)
    fig.colorbar(image, ax=ax, label=bar_label)
    if grid.size <= 100:  # cell labels stay legible only on small grids
        for (i, j), v in np.ndenumerate(grid):
            dark = np.isfinite(v) and np.dot(image.to_rgba(v)[:3], (0.299, 0.587, 0.114)) < 0.5
            ax.text(j, i, labels[i][j], ha="center", va="center", fontsize=CELL_FONT,
                    color="white" if dark else "black", gid="cell")
    if default is not None:  # a frame around the cell keeps its value legible
        from matplotlib.patches import Rectangle
        for colour_, width in (("black", 2.2), ("white", 1.0)):
            ax.add_patch(Rectangle((default[0] - 0.46, default[1] - 0.46), 0.92, 0.92,
                                   fill=False, ec=colour_, lw=width))
    alphas, betas = axes_values
    tick = lambda x: f"{x:.2g}" if x < 100 else f"{x:.0f}"  # noqa: E731
    ax.set_xticks(range(len(alphas)), [tick(a) for a in alphas], fontsize=8)
    ax.set_yticks(range(len(betas)), [tick(b) for b in betas], fontsize=8)
    ax.set_xlabel("α [1/s]")
    ax.set_ylabel("β [1/s]")


def draw(plt, np, style, rows, scene):
    """The figure of error, drift and steps over the (alpha, beta) grid of baumgarte_study.csv's
    rows, each on a log colour scale; or None and why there is none."""
    from matplotlib.colors import LogNorm
    rows = [r for r in rows if num(r.get("alpha")) is not None and num(r.get("beta")) is not None]
    if not rows:
        return None, "baumgarte_study.csv absent or without grid points"
    alphas = sorted({num(r["alpha"]) for r in rows})
    betas = sorted({num(r["beta"]) for r in rows})
    shape = (len(betas), len(alphas))
    grids = {k: np.full(shape, np.nan) for k in ("error_u", "max_drift_position", "steps")}
    texts = {k: [[""] * len(alphas) for _ in betas] for k in grids}
    default = None
    for r in rows:
        i, j = betas.index(num(r["beta"])), alphas.index(num(r["alpha"]))
        if num(r.get("default")) == 1:
            default = (j, i)
        for k in grids:
            if r.get("status") != "ok":
                texts[k][i][j] = "×"  # grey and crossed: a word overflowed the cell
                continue
            v = num(r.get(k))
            texts[k][i][j] = "–" if v is None else (f"{v:.0f}" if k == "steps" else
                                                      f"{v:.0e}".replace("e-0", "e-") if v else "0")
            if v is not None:
                grids[k][i, j] = v
    panels = [(k, title, bar) for k, title, bar in (
        ("error_u", "displacement error", "relative max-norm error"),
        ("max_drift_position", "max position drift", "max |Φ| (units of the rows)"),
        ("steps", "integrator steps", "steps")) if np.isfinite(grids[k]).any()]
    if not panels:
        return None, "no successful grid point"
    fig, axes = plt.subplots(1, len(panels), figsize=(style.PAGE_WIDTH, 2.9), squeeze=False)
    for ax, (k, title, bar) in zip(axes[0], panels):
        grid = grids[k]
        positive = grid[np.isfinite(grid) & (grid > 0)]
        if not positive.size:
            ax.set_axis_off()
            ax.set_title(f"{title}: all zero")
            continue
        lo, hi = positive.min(), positive.max()
        grid = np.where(grid <= 0, lo / 10, grid)  # exact zeros: white, below the scale
        heat_map(plt, np, fig, ax, grid, texts[k], LogNorm(lo / 2, hi * 2) if lo == hi else
                 LogNorm(lo, hi), "viridis", bar, (alphas, betas), default)
        ax.set_title(title)
    style.title(fig, f"{scene}\nBaumgarte gains (e'' + 2α e' + β² e = 0 on the constraint "
                     "error); framed: default; grey ×: failed")
    style.fit(fig)
    shrink_to_cells(fig)
    return fig, None


def shrink_to_cells(fig):
    """Cell labels in a smaller font where they would overflow their cell (a wide number of
    steps in a narrow panel)."""
    renderer = fig.canvas.get_renderer()
    for text in fig.findobj(lambda a: getattr(a, "get_gid", lambda: None)() == "cell"):
        x, y = text.get_position()
        cell = text.axes.transData.transform([(x - 0.5, y - 0.5), (x + 0.5, y + 0.5)])
        room = abs(cell[1][0] - cell[0][0]) * 0.9
        while text.get_fontsize() > 4 and text.get_window_extent(renderer).width > room:
            text.set_fontsize(text.get_fontsize() - 0.5)
