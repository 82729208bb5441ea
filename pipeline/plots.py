"""Matplotlib without a display, with one consistent look for every plot in results/."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def figure(width=6.4, height=4.2):
    fig, ax = plt.subplots(figsize=(width, height), dpi=110)
    ax.grid(True, alpha=0.3)
    return fig, ax


def save(fig, path, tight: bool = True) -> None:
    """Saves atomically (pipeline.artifacts.write_atomic): a full disk leaves the old plot or
    none, never a truncated PNG. tight=False keeps a layout placed by hand (colour bars on
    axes of their own)."""
    from pathlib import Path
    from pipeline.artifacts import write_atomic
    if tight:
        fig.tight_layout()
    try:
        write_atomic(path, lambda tmp: fig.savefig(tmp, format=Path(path).suffix.lstrip(".") or None,
                                                   metadata={"Software": None}))
    finally:
        plt.close(fig)


def plain_log_ticks(axis, subs=(1.0, 2.0, 5.0)) -> None:
    """Label a log axis with plain numbers at 1, 2 and 5 times each power of ten (0.2, 0.5, 1).
    Over a decade or less matplotlib labels its minor ticks as 2×10⁻¹, unreadable at tick size."""
    from matplotlib import ticker
    axis.set_major_locator(ticker.LogLocator(base=10.0, subs=subs))
    axis.set_major_formatter(ticker.FormatStrFormatter("%g"))
    axis.set_minor_formatter(ticker.NullFormatter())
