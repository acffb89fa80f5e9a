#!/usr/bin/python3
"""Counts the crowd's top-top and top-wall touches in a `simulate --csv` time series of a
tippe_crowd_N scene (bench/peers/multi_top_scene.py --crowd), by the rule of PairMonitor in
bench/peers/tippe_top_scene.h, which the peer engines apply inside their stepping loop:

    bench/peers/crowd_contacts.py N CSV          # prints one JSON object

Two tops touch in a step when a sphere of one (big sphere R1 at a1, peg R2 at a2 along e3 from
the centre of mass) is within TOUCH_GAP of a sphere of the other; a top touches a wall when one
of its spheres is within TOUCH_GAP of the wall's plane. The CSV must have every step
(`--decimate 1`): a contact between two tops may last a single step. Fields: touch_steps (steps
with a touching pair), pair_touch_steps (touching pairs summed over the steps), pair_onsets (a
pair touching that did not touch in the step before), pairs_touched (distinct pairs),
max_touching_pairs, wall_onsets, wall_touch_steps, max_coordinate (the largest |x| or |y| of a
centre of mass: inside the arena it stays below the half-width); and the simulator's own max_closed_contacts
(ground, walls and tops; the start row t = 0 is not a step).
"""
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
from multi_top_scene import A1, A2, R1, R2, TOUCH_GAP, crowd_walls  # noqa: E402

CHUNK = 400  # rows per vectorised block


def count(n, lines):
    """lines: an iterator over the CSV's lines, the header first."""
    header = next(lines).strip().split(",")
    col = {name: k for k, name in enumerate(header)}
    pose = np.array([[col[f"top{i}/{c}"] for c in ("x", "y", "z", "qx", "qy", "qz", "qw")]
                     for i in range(n)])                                  # n x 7
    c_closed = col["closed_contacts"]
    walls = crowd_walls(n)
    normals = np.array([w[1] for w in walls])                             # 4 x 3
    offsets = np.array([w[2] for w in walls])                             # 4
    radius = np.array([R1, R2])
    offset = np.array([A1, A2])
    reach = (radius[:, None] + radius[None, :] + TOUCH_GAP) ** 2          # 2 x 2
    upper = np.triu(np.ones((n, n), dtype=bool), 1)
    out = dict(touch_gap=TOUCH_GAP, touch_steps=0, pair_touch_steps=0, pair_onsets=0,
               pairs_touched=0, max_touching_pairs=0, wall_onsets=0, wall_touch_steps=0,
               max_coordinate=0.0, max_closed_contacts=0, steps=0)
    touched = np.zeros((n, n), dtype=bool)
    previous_pairs = np.zeros((n, n), dtype=bool)
    previous_walls = np.zeros((n, len(walls)), dtype=bool)
    first = True

    def block(rows):
        nonlocal previous_pairs, previous_walls, touched
        a = np.array(rows)                                                # k x columns
        p = a[:, pose]                                                    # k x n x 7
        x, y, z, w = p[..., 3], p[..., 4], p[..., 5], p[..., 6]
        n2 = w * w + x * x + y * y + z * z
        e3 = np.stack([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)], -1) / n2[..., None]
        centres = p[..., None, :3] + offset[None, None, :, None] * e3[..., None, :]   # k x n x 2 x 3
        # pairs: first the centres of mass (a top reaches at most a2 + R2 from its own), then for
        # the candidates the squared distances of sphere a of top i and sphere b of top j
        s = p[..., :3]
        dc = s[:, :, None, :] - s[:, None, :, :]
        near = (np.einsum("kijx,kijx->kij", dc, dc) <= (2 * (A2 + R2) + TOUCH_GAP) ** 2) & upper
        kk, ii, jj = np.nonzero(near)
        d = centres[kk, ii][:, :, None, :] - centres[kk, jj][:, None, :, :]    # m x 2 x 2 x 3
        hit = (np.einsum("mabx,mabx->mab", d, d) <= reach).any(axis=(1, 2))
        pairs = np.zeros_like(near)
        pairs[kk[hit], ii[hit], jj[hit]] = True                           # k x n x n
        # walls: signed distance of every sphere to every plane minus its radius, k x n x 2 x 4
        gaps = np.einsum("kiax,wx->kiaw", centres, normals) - offsets - radius[None, None, :, None]
        at_wall = (gaps <= TOUCH_GAP).any(axis=2)                         # k x n x 4
        counts = pairs.sum(axis=(1, 2))
        out["touch_steps"] += int((counts > 0).sum())
        out["pair_touch_steps"] += int(counts.sum())
        out["max_touching_pairs"] = max(out["max_touching_pairs"], int(counts.max()))
        before = np.concatenate([previous_pairs[None], pairs[:-1]])
        out["pair_onsets"] += int((pairs & ~before).sum())
        touched |= pairs.any(axis=0)
        before = np.concatenate([previous_walls[None], at_wall[:-1]])
        out["wall_onsets"] += int((at_wall & ~before).sum())
        out["wall_touch_steps"] += int(at_wall.any(axis=(1, 2)).sum())
        out["max_coordinate"] = max(out["max_coordinate"], float(np.abs(p[..., :2]).max()))
        previous_pairs, previous_walls = pairs[-1], at_wall[-1]
        out["max_closed_contacts"] = max(out["max_closed_contacts"], int(a[:, c_closed].max()))
        out["steps"] += len(rows)

    rows = []
    for line in lines:
        if first:  # the start, t = 0, is not a step (the crowd starts 15 mm apart: nothing touches)
            first = False
            continue
        values = np.fromstring(line, sep=",")
        rows.append(values)
        if len(rows) == CHUNK:
            block(rows)
            rows = []
    if rows:
        block(rows)
    out["pairs_touched"] = int(touched.sum())
    return out


def main():
    if len(sys.argv) != 3 or not sys.argv[1].isdigit():
        sys.exit("usage: bench/peers/crowd_contacts.py N CSV")
    with open(sys.argv[2]) as f:
        print(json.dumps(count(int(sys.argv[1]), iter(f))))


if __name__ == "__main__":
    main()
