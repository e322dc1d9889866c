"""IDA curves and a lognormal fragility fit from a sweep's results (docs/sweep.md, [ida]): the
intensity (the [scale] column) against a kept column's peak, one line per record with the median
and the 16 and 84 % fractiles across records at each intensity; and the probability that the peak
reaches the limit state, fitted by maximum likelihood as a lognormal CDF in the intensity (Baker,
"Efficient analytical fragility function fitting using dynamic structural analysis", Earthquake
Spectra 31(1), 2015). A failed run counts as reaching the limit (a collapse) and draws no point.
"""

import json
import math
import os

import numpy as np

from .sweep_file import _fail

_IDA_KEYS = ("response", "limit", "intensity_label", "response_label")


def default_labels(intensity, response, scale=None):
    """The axes' labels when [ida] names none: what the intensity is (with Sa's period and damping
    from [scale]) and that both are in the scene's units (condyn has no units of its own)."""
    scale = scale or {}
    if intensity == "sa":
        what = (f"Sa(T = {scale.get('period', float('nan')):g}, "
                f"damping {scale.get('damping', 0.05):g}), in the scene's acceleration units")
    elif intensity == "pga":
        what = "PGA, in the scene's acceleration units"
    else:
        what = "scale factor on each record"
    return {"intensity": what, "response": f"peak |{response}|, in the scene's units"}


def read_ida(path, table, sweep):
    """The [ida] table checked: (column, limit or None, axis labels), or None without [ida].
    Needs [records] and [scale] (the record and intensity of each run) and a kept column."""
    ida = table.get("ida")
    if ida is None:
        return None
    if not isinstance(ida, dict):
        _fail(path, "ida", "expected a table ([ida] with response and limit)")
    for k in ida:
        if k not in _IDA_KEYS:
            _fail(path, f"ida.{k}", f"unknown key ([ida] has {', '.join(_IDA_KEYS)})")
    keys = [a.key for a in sweep.axes]
    if "record" not in keys or not ({"scale", "pga", "sa"} & set(keys)):
        _fail(path, "ida", "needs [records] and [scale]: the curves are a record's intensity "
              "against its response")
    response = ida.get("response")
    if response not in sweep.peaks:
        _fail(path, "ida.response", f"expected one of the kept columns [keep] peaks "
              f"({', '.join(sweep.peaks) or 'none'}) (got {response!r})")
    limit = ida.get("limit")
    if limit is not None and (isinstance(limit, bool) or not isinstance(limit, (int, float))
                              or not math.isfinite(limit) or limit <= 0):
        _fail(path, "ida.limit", f"expected a positive number (got {limit!r})")
    scale = table.get("scale") if isinstance(table.get("scale"), dict) else {}
    intensity = next((k for k in ("pga", "sa") if k in scale), "scale")
    labels = default_labels(intensity, response, scale)
    for axis in ("intensity", "response"):
        label = ida.get(f"{axis}_label")
        if label is None:
            continue
        if not isinstance(label, str) or not label.strip():
            _fail(path, f"ida.{axis}_label", f"expected the axis label, a non-empty string "
                  f"(got {label!r})")
        labels[axis] = label
    return response, limit, labels


def ida_points(columns, rows, response):
    """{record: (intensities, peaks)} of the runs that reached t_end, by intensity; and every
    run as (intensity, reached the limit?) input: (intensity, peak or inf for a failure)."""
    col = {name: j for j, name in enumerate(columns)}
    intensity = next(k for k in ("pga", "sa", "scale") if k in col)
    runs = []
    for r in rows:
        peak = float(r[col["peak_" + response]]) if r[col["status"]] == "ok" else math.inf
        runs.append((r[col["record"]], float(r[col[intensity]]), peak))
    curves = {}
    for record, im, peak in sorted(runs):
        if math.isfinite(peak):
            curves.setdefault(record, ([], []))
            curves[record][0].append(im)
            curves[record][1].append(peak)
    return intensity, curves, [(im, peak) for _, im, peak in runs]


def fragility_fit(runs, limit):
    """(theta, beta) of P(peak >= limit | im) = Phi(ln(im / theta) / beta), by maximum likelihood
    over the runs (each a Bernoulli trial); None when every run or none reaches the limit."""
    from scipy.optimize import minimize
    from scipy.stats import norm

    im = np.array([r[0] for r in runs])
    hit = np.array([r[1] >= limit for r in runs])
    if hit.all() or not hit.any():
        return None

    def minus_log_likelihood(p):
        prob = np.clip(norm.cdf((np.log(im) - p[0]) / math.exp(p[1])), 1e-300, 1 - 1e-16)
        return -np.sum(np.where(hit, np.log(prob), np.log1p(-prob)))

    start = [float(np.mean(np.log(im))), math.log(0.4)]
    best = minimize(minus_log_likelihood, start, method="Nelder-Mead",
                    options={"xatol": 1e-10, "fatol": 1e-12, "maxiter": 4000})
    return math.exp(best.x[0]), math.exp(best.x[1])


def write_ida(folder, columns, rows, response, limit, labels=None):
    """DIR/ida.png and .pdf, and with a limit DIR/fragility.png, .pdf and fragility.json; the axes
    labelled by `labels` ({intensity, response}: read_ida's, default_labels when None).
    Returns the fit (theta, beta) or None."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    intensity, curves, runs = ida_points(columns, rows, response)
    labels = labels or default_labels(intensity, response)
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    for record, (ims, peaks) in curves.items():
        ax.plot(peaks, ims, "-o", color="0.7", lw=0.8, ms=2.5)
    levels = sorted({im for im, _ in runs})
    stripes = [np.array([p for im, p in runs if im == level]) for level in levels]
    for q, style, label in ((50, "-", "median"), (16, "--", "16 %"), (84, "--", "84 %")):
        # Counted fractiles (no interpolation): a failed run's infinite peak stays one.
        ax.plot([np.percentile(s, q, method="inverted_cdf") for s in stripes], levels, style,
                color="k", lw=1.6,
                label=f"{label} across records")
    if limit is not None:
        ax.axvline(limit, color="tab:red", lw=1.0, label=f"limit state {limit:g}")
    ax.set_xlabel(labels["response"])
    ax.set_ylabel(labels["intensity"])
    ax.set_title(f"IDA curves: {len(curves)} records (grey), failed runs left out")
    ax.legend(loc="lower right", fontsize=8)
    _save(fig, os.path.join(folder, "ida"))
    plt.close(fig)
    if limit is None:
        return None
    fit = fragility_fit(runs, limit)
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    fractions = [np.mean(s >= limit) for s in stripes]
    ax.plot(levels, fractions, "o", color="k", label="fraction of records reaching the limit")
    if fit is not None:
        from scipy.stats import norm
        x = np.linspace(min(levels) * 0.5, max(levels) * 1.2, 200)
        ax.plot(x, norm.cdf(np.log(x / fit[0]) / fit[1]), "-", color="tab:blue",
                label=f"lognormal fit: median {fit[0]:.3g}, beta {fit[1]:.3g}")
    ax.set_xlabel(labels["intensity"])
    ax.set_ylabel(f"P(peak |{response}| >= {limit:g})")
    ax.set_ylim(-0.02, 1.02)
    ax.set_title("Fragility (maximum likelihood, Baker 2015)")
    ax.legend(loc="lower right", fontsize=8)
    _save(fig, os.path.join(folder, "fragility"))
    plt.close(fig)
    with open(os.path.join(folder, "fragility.json"), "w") as f:
        json.dump({"response": response, "limit": limit, "intensity": intensity,
                   "median": fit[0] if fit else None, "beta": fit[1] if fit else None,
                   "runs": len(runs)}, f, indent=1)
    return fit


def _save(fig, stem):
    fig.tight_layout()
    for ext in ("png", "pdf"):
        fig.savefig(f"{stem}.{ext}", dpi=150)
