"""The plots' common parts: where they are saved (docs/img) and the panel of clustered particles."""

import numpy as np

from mpisph import pairing
from mpisph.particles import MOVING

from .runs import ROOT


DOCS = ROOT / "docs"
IMG = DOCS / "img"


def save(fig, image):
    fig.tight_layout()
    fig.savefig(IMG / image, dpi=90)
    return image


def clustered_panel(fig, ax, frame, title, field="plastic_strain", axes=(0, 1)):
    """The material particles of ``frame`` coloured by ``field`` (its colours capped at its 99th
    percentile), the clustered ones red."""
    moving = frame["kind"] == MOVING
    x, c = frame["x"][moving], frame[field][moving]
    sc = ax.scatter(x[:, axes[0]], x[:, axes[1]], c=c, s=0.3, cmap="viridis",
                    vmax=max(np.percentile(c, 99), c.min() + 1e-12))
    i, _ = pairing.clustered_pairs(frame)
    ax.plot(frame["x"][i, axes[0]], frame["x"][i, axes[1]], "r.", ms=1.5)
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=7)
    fig.colorbar(sc, ax=ax, shrink=0.6)
