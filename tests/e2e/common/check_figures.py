#!/usr/bin/env python3
"""The report's figure rules (scripts/sections/common/plot.py,
figure_problems), each broken once on a figure made here, and a figure that
keeps them all: a field image without axis labels, one without a colour bar,
a colour bar without a label, a shared colour bar (allowed), an RGB picture
(needs no bar), a y label over the neighbouring panel, two titles over each other, a
4-pt legend.

usage: check_figures.py.  Prints "ok" and exits 0, or what failed and 1."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                                "scripts"))
from sections.common.plot import figure_problems, pyplot  # noqa: E402

import numpy as np  # noqa: E402

plt = pyplot()
Z = np.arange(12.0).reshape(3, 4)
fails = []


def expect(name, fig, want):
    """want: a word every problem line must hold, None: no problem."""
    got = figure_problems(fig)
    plt.close(fig)
    if want is None and got:
        fails.append(f"{name}: unexpected {got}")
    elif want is not None and not any(want in g for g in got):
        fails.append(f"{name}: expected a problem with '{want}', got {got}")


def good():
    fig, ax = plt.subplots()
    im = ax.imshow(Z)
    ax.set_xlabel("x"), ax.set_ylabel("y")
    fig.colorbar(im, ax=ax, label="d")
    return fig, ax, im


fig, _, _ = good()
expect("all rules kept", fig, None)

fig, ax = plt.subplots()
im = ax.imshow(Z)
fig.colorbar(im, ax=ax, label="d")
expect("no axis labels", fig, "without x and y labels")

fig, ax = plt.subplots()
im = ax.pcolormesh(Z)
ax.set_xlabel("x"), ax.set_ylabel("y")
expect("mesh without colour bar", fig, "without a colour bar")

fig, ax = plt.subplots()
im = ax.imshow(Z)
ax.set_xlabel("x"), ax.set_ylabel("y")
fig.colorbar(im, ax=ax)
expect("unlabelled colour bar", fig, "colour bar has no label")

fig, axs = plt.subplots(1, 2)
for a in axs:
    im = a.imshow(Z, vmin=0, vmax=11)
    a.set_xlabel("x"), a.set_ylabel("y")
fig.colorbar(im, ax=axs.tolist(), label="d")
expect("one bar shared by two fields of the same limits", fig, None)

fig, axs = plt.subplots(1, 2)
axs[0].imshow(Z, vmin=0, vmax=5)
im = axs[1].imshow(Z, vmin=0, vmax=11)
for a in axs:
    a.set_xlabel("x"), a.set_ylabel("y")
fig.colorbar(im, ax=axs[1], label="d")
expect("a second field of other limits has no bar", fig, "without a colour bar")

fig, ax = plt.subplots()
ax.imshow(np.zeros((3, 4, 3)))
ax.axis("off")
expect("an RGB picture with its axis off", fig, None)

fig, axs = plt.subplots(1, 2, figsize=(4, 2))
for a in axs:
    a.plot([0, 1], [0, 1])
axs[1].set_ylabel("a very long label that runs into the left panel", fontsize=14,
                  labelpad=60)
expect("label over the next panel", fig, "overlaps the axes")

fig, axs = plt.subplots(1, 2, figsize=(4, 2))
for a in axs:
    a.plot([0, 1], [0, 1])
    a.set_title("a title far too long for its panel, running into the next one")
expect("titles over each other", fig, "overlaps the label")

fig, ax = plt.subplots()
ax.plot([0, 1], [0, 1], label="c")
ax.legend(fontsize=4)
expect("tiny legend", fig, "legend text")

if fails:
    print("\n".join(fails))
    sys.exit(1)
print("ok")
