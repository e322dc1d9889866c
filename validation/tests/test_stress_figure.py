"""plot_stress.py: the stress map's labels inside the figure and apart, and a stress.csv that
condyn stress would not have written named with the problem (exit 2), never a traceback."""
import matplotlib.pyplot as plt
import pytest

import plot_stress
from layout import problems

VERDICTS = ["holds", "inaccurate", "failed", "refused", "holds", "holds", "failed", "holds"]


def write_stress(d):
    rows = ["case,family,label,scheme,status,error_u"]
    for family in ("stiffness", "redundancy", "long_horizon"):
        for k in range(3):
            for scheme, status in zip(plot_stress.SCHEMES, VERDICTS):
                error = f"{10.0 ** -k:g}" if status in ("holds", "inaccurate") else ""
                label = f"stiffness ratio 1e{3 * k} (the longest label)"
                rows.append(f"{family}_{k},{family},{label},{scheme},{status},{error}")
    (d / "stress.csv").write_text("\n".join(rows) + "\n")


def test_stress_map_labels_inside_and_apart(tmp_path, monkeypatch):
    write_stress(tmp_path)
    saved = []
    monkeypatch.setattr(plt.Figure, "savefig", lambda fig, *a, **k: saved.append(fig))
    assert plot_stress.main(["plot_stress.py", str(tmp_path)]) == 0
    assert problems(saved[0]) == []  # the slanted scheme names' boxes ran into each other
    plt.close("all")


@pytest.mark.parametrize("content, expected", [
    (b"case,family\n\xff\n", "stress.csv: not UTF-8 text (byte 0xff)"),
    (b"case,scheme\nx,ggl\n", "stress.csv: no column family, label, status"),
    (b"case,family,label,scheme,status\nx,f,l,ggl,holds,extra\n", "stress.csv:2: the row's"),
])
def test_bad_stress_csv_named_exit_2(tmp_path, capsys, content, expected):
    (tmp_path / "stress.csv").write_bytes(content)
    assert plot_stress.main(["plot_stress.py", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert expected in err and "Traceback" not in err
