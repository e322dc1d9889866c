"""Geometry checks of a laid-out figure, through matplotlib's renderer (not pixels): what a
reader of the printed figure would see clipped or run together."""

from matplotlib.text import Text

# Two labels closer than this [pt] read as one: the gap the trial saw between neighbouring
# x labels of error_steps was under 2 pt.
MIN_GAP_PT = 1.0


def drawn_tick_labels(fig):
    """The tick labels matplotlib draws (those of ticks inside the view), and all of them."""
    drawn, every = set(), set()
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            for tick in axis.get_major_ticks() + axis.get_minor_ticks():
                every.update((id(tick.label1), id(tick.label2)))
            for tick in axis._update_ticks():  # those inside the view interval
                drawn.update(id(t) for t in (tick.label1, tick.label2) if t.get_visible())
    return drawn, every


def visible_texts(fig):
    renderer = fig.canvas.get_renderer()
    fig.draw(renderer)  # ticks and their labels exist once drawn
    drawn, every = drawn_tick_labels(fig)
    texts, seen = [], set()
    for text in fig.findobj(Text):
        if not text.get_visible() or not str(text.get_text()).strip():
            continue
        if id(text) in seen or (id(text) in every and id(text) not in drawn):
            continue
        seen.add(id(text))
        if not text.get_figure() or (text.axes is not None and not text.axes.get_visible()):
            continue
        box = text.get_window_extent(renderer)
        if box.width > 0 and box.height > 0:
            texts.append((text, box))
    return texts


def problems(fig):
    """Labels outside the figure, and pairs of labels that overlap or nearly touch."""
    found = []
    bounds = fig.bbox
    gap = MIN_GAP_PT * fig.dpi / 72.0
    texts = visible_texts(fig)
    for text, box in texts:
        if box.x0 < bounds.x0 - 0.5 or box.x1 > bounds.x1 + 0.5 or box.y0 < bounds.y0 - 0.5 or \
                box.y1 > bounds.y1 + 0.5:
            found.append(f"outside the figure: {text.get_text()!r} {box.bounds}")
    for i, (a, box_a) in enumerate(texts):
        for b, box_b in texts[i + 1:]:
            if box_a.x0 - gap < box_b.x1 and box_b.x0 - gap < box_a.x1 and \
                    box_a.y0 - gap < box_b.y1 and box_b.y0 - gap < box_a.y1:
                found.append(f"labels overlap or touch: {a.get_text()!r} and {b.get_text()!r}")
    return found
