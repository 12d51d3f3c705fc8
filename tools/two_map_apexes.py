#!/usr/bin/python3
"""Draws docs/images/two_map_apexes.svg: where two_map_bound puts its two
shadow maps (Shypula 2008, ch. 8, figures 8.4-8.5), in a cross-section
through the light's axis (techniques/two_map/apex_placement.h).

A light of half-width l at depth 0, the casters' extent of half-width c at
depth D, a receiver plane at depth R. The penumbra apex is where the lines
from each light edge to the extent's opposite edge cross (z_p = D l / (c + l),
in front of the light); the umbra apex where the lines to the same edge
cross (z_u = -D l / (c - l), behind the light when c > l). Hidden from the
penumbra apex: the penumbra and umbra of an occluder as wide as the extent;
hidden from the umbra apex: its umbra.

Usage: tools/two_map_apexes.py [OUT.svg]   (Debian's python3-matplotlib)
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

L, C, D, R = 1.0, 2.0, 4.0, 9.0  # light half-width, extent half-width, depths


def line_x(x0, z0, x1, z1, z):
    return x0 + (x1 - x0) * (z - z0) / (z1 - z0)


def main(out):
    matplotlib.rcParams["svg.fonttype"] = "none"
    matplotlib.rcParams["svg.hashsalt"] = "two_map_apexes"
    zp = D * L / (C + L)
    zu = -D * L / (C - L)
    fig, ax = plt.subplots(figsize=(7.0, 5.6))
    # Depth grows downwards, as the light shines.
    ax.invert_yaxis()
    ax.plot([-L, L], [0, 0], color="#e0a000", lw=5, solid_capstyle="butt", label="light (2l)")
    ax.plot([-C, C], [D, D], color="#445", lw=4, solid_capstyle="butt",
            label="casters' extent (2c)")
    ax.plot([-7, 7], [R, R], color="#999", lw=1.5)
    ax.text(6.9, R - 0.15, "receiver", ha="right", va="bottom", color="#666")
    # Penumbra frustum: light edges to opposite extent edges, through the apex.
    for sx in (-1, 1):
        x_r = line_x(-sx * L, 0, sx * C, D, R)
        ax.plot([-sx * L, x_r], [0, R], color="#c0392b", lw=1)
        # Umbra frustum: light edges to the same extent edges.
        x_u = line_x(sx * L, 0, sx * C, D, R)
        ax.plot([zu and line_x(sx * L, 0, sx * C, D, zu), x_u], [zu, R], color="#2962a8",
                lw=1, ls="--")
    x_out = line_x(-L, 0, C, D, R)
    x_in = line_x(L, 0, C, D, R)
    ax.fill_between([-x_in, x_in], R, R + 0.35, color="#222", lw=0)
    ax.fill_between([x_in, x_out], R, R + 0.35, color="#aaa", lw=0)
    ax.fill_between([-x_out, -x_in], R, R + 0.35, color="#aaa", lw=0)
    ax.text(0, R + 0.7, "umbra:\nhidden from both", ha="center", va="top", fontsize=8)
    ax.text(0.5 * (x_in + x_out), R + 0.7, "penumbra:\nhidden from the\npenumbra apex", ha="center",
            va="top", fontsize=8)
    ax.plot([0], [zp], "o", color="#c0392b")
    ax.annotate(f"penumbra apex\nz_p = D·l/(c+l) = {zp:.2f}", (0, zp), (1.6, zp - 0.9),
                arrowprops={"arrowstyle": "->", "color": "#c0392b"}, color="#c0392b")
    ax.plot([0], [zu], "o", color="#2962a8")
    ax.annotate(f"umbra apex\nz_u = −D·l/(c−l) = {zu:.2f}", (0, zu), (1.6, zu + 0.2),
                arrowprops={"arrowstyle": "->", "color": "#2962a8"}, color="#2962a8")
    ax.set_xlim(-7, 7)
    ax.set_ylim(R + 2.6, zu - 0.8)
    ax.set_xlabel("across the light's axis")
    ax.set_ylabel("depth along the light's axis")
    ax.set_title(f"two_map_bound's apexes: l = {L:g}, c = {C:g}, D = {D:g}")
    ax.legend(loc="upper left", fontsize=8)
    ax.set_aspect("equal")
    fig.tight_layout()
    fig.savefig(out, metadata={"Date": None})


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "docs/images/two_map_apexes.svg")
