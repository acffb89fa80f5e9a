#!/usr/bin/python3
"""Table row and plot per shipped scene, from the runs `scripts/demo` makes with
`simulate --urdf urdf/<scene>.urdf --initial config/<scene>.yaml --csv out/<scene>.csv
--summary out/<scene>.json` (per-body CSV columns, see `simulate --help`).

usage: scripts/scene_report.py OUT_DIR SCENE ...

For each scene it plots the quantity that scene is known for (docs/scenes.md) into
OUT_DIR/<scene>.png and prints one table row: the quantity at the start and the end, what the
scene shows (column "effect", below), the energy lost, the deepest penetration, iterations per
step and the CPU time of the stepping.
  euler_disk     inclination alpha of the disc (axis from the vertical) and precession rate Omega;
                 effect: the energy drift dE/dt, the slope of a least-squares line through E(t)
                 over the whole run [J/s] (and in % of E(0) per second)
  rattleback     vertical spin w_z; effect: the first reversal, the first time w_z is beyond
                 0.05 rad/s with the sign opposite to the start (as test/scenes/rattleback_test.cpp;
                 "none" if it never is), and the peak reversed spin, the extreme of w_z on that
                 side, with its time
  spinning_egg   inclination of the polar axis e3 from the vertical
  classic_top    inclination of the axis and precession rate
  tippe_top_duel x of both centres and the energy
  coin           vertical spin w_z
  die, d20       height of the centre and speed
Uses Debian's python3-matplotlib and numpy; runs headless.
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, data = rows[0], np.array(rows[1:], dtype=float)
    return {name: data[:, k] for k, name in enumerate(header)}


def bodies_of(columns):
    return sorted({name.split("/")[0] for name in columns if name.endswith("/qw")})


def axis_world(c, body, axis=2):
    """Column `axis` of the rotation matrix of the body's quaternion: e_axis in the world."""
    x, y, z, w = (c[f"{body}/q{k}"] for k in "xyzw")
    if axis == 2:
        return np.stack([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)])
    return np.stack([1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)])


def inclination(c, body):
    e3 = axis_world(c, body)
    return np.arctan2(np.hypot(e3[0], e3[1]), e3[2])


def precession_rate(c, body):
    """d/dt of the azimuth of the axis' horizontal projection [rad/s]."""
    e3 = axis_world(c, body)
    phi = np.unwrap(np.arctan2(e3[1], e3[0]))
    return np.gradient(phi, c["t"])


def plot(path, title, t, curves, ylabel):
    fig, ax = plt.subplots(figsize=(6.4, 3.6))
    for label, values in curves:
        ax.plot(t, values, label=label, lw=1.2)
    ax.set_xlabel("t [s]")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(alpha=0.3)
    if len(curves) > 1:
        ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


REVERSAL_THRESHOLD = 0.05  # rad/s: a spin reversal counts beyond it (rattleback_test.cpp)


def spin_reversal(t, wz):
    """(time of the first reversal, peak reversed spin, its time) of w_z(t), or None: reversed
    means the sign opposite to w_z[0] and |w_z| > REVERSAL_THRESHOLD."""
    sign = np.sign(wz[0])
    reversed_ = np.nonzero(sign * wz < -REVERSAL_THRESHOLD)[0]
    if sign == 0 or len(reversed_) == 0:
        return None
    peak = np.argmin(sign * wz)
    return t[reversed_[0]], wz[peak], t[peak]


def energy_drift(t, energy):
    """dE/dt [J/s]: slope of the least-squares line through E(t)."""
    return np.polyfit(t, energy, 1)[0] if len(t) > 1 and t[-1] > t[0] else float("nan")


def quantity(scene, c):
    """(name, unit, curves, start, end, effect) of the scene's quantity."""
    t = c["t"]
    body = bodies_of(c)[0]
    if scene == "euler_disk":
        alpha = np.degrees(inclination(c, body))
        omega = precession_rate(c, body)
        drift = energy_drift(t, c["energy"])
        relative = 100 * drift / c["energy"][0] if c["energy"][0] > 0 else float("nan")
        return ("alpha / Omega", "deg, rad/s", [("alpha [deg]", alpha), ("Omega [rad/s]", omega)],
                f"{alpha[0]:.1f} deg", f"{alpha[-1]:.2f} deg, Omega {omega[-1]:.1f}",
                f"dE/dt {drift:+.2e} J/s ({relative:+.2f} %/s)")
    if scene in ("rattleback", "coin"):
        wz = c[f"{body}/wz"]
        effect = ""
        if scene == "rattleback":
            r = spin_reversal(t, wz)
            effect = ("reversal none" if r is None else
                      f"reversal {r[0]:.3f} s, peak {r[1]:+.2f} rad/s at {r[2]:.2f} s")
        return ("w_z", "rad/s", [("w_z [rad/s]", wz)], f"{wz[0]:.2f}", f"{wz[-1]:.3f}", effect)
    if scene in ("spinning_egg", "classic_top"):
        theta = np.degrees(inclination(c, body))
        return ("inclination", "deg", [("theta [deg]", theta)], f"{theta[0]:.1f}",
                f"{theta[-1]:.1f}", "")
    if scene == "tippe_top_duel":
        curves = [(f"{b} x [mm]", 1e3 * c[f"{b}/x"]) for b in bodies_of(c)]
        return ("x of the centres", "mm", curves, "", "", "")
    if scene in ("die", "d20"):
        z = 1e3 * c[f"{body}/z"]
        speed = np.sqrt(sum(c[f"{body}/v{k}"] ** 2 for k in "xyz"))
        return ("height / speed", "mm, m/s", [("z [mm]", z), ("|v| [m/s]", speed)],
                f"z {z[0]:.1f} mm", f"z {z[-1]:.2f} mm, |v| {speed[-1]:.1e}", "")
    theta = np.degrees(inclination(c, body))
    return ("inclination", "deg", [("theta [deg]", theta)], f"{theta[0]:.1f}", f"{theta[-1]:.1f}",
            "")


def main():
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    out, scenes = sys.argv[1], sys.argv[2:]
    rows = [("scene", "quantity", "start", "end", "effect", "energy lost", "max penetration",
             "iter/step", "cpu s", "sim s")]
    for scene in scenes:
        c = read_csv(os.path.join(out, scene + ".csv"))
        with open(os.path.join(out, scene + ".json")) as f:
            s = json.load(f)
        name, unit, curves, start, end, effect = quantity(scene, c)
        plot(os.path.join(out, scene + ".png"), f"{scene}: {name}", c["t"], curves, unit)
        e0, e1 = s["energy_initial"], s["energy_final"]
        lost = f"{100 * (e0 - e1) / e0:.1f} %" if e0 > 0 else f"{e0 - e1:.3g} J"
        rows.append((scene, name, start, end, effect, lost,
                     f"{1e3 * s['max_penetration']:.4f} mm",
                     f"{s['mean_iterations']:.2f}", f"{s['cpu_time_s']:.3f}",
                     f"{s['duration']:g}"))
    widths = [max(len(r[k]) for r in rows) for k in range(len(rows[0]))]
    for i, r in enumerate(rows):
        print("  ".join(v.ljust(w) for v, w in zip(r, widths)))
        if i == 0:
            print("  ".join("-" * w for w in widths))
    if "rattleback" in scenes:
        print(f"effect, rattleback: reversal = first time w_z is beyond {REVERSAL_THRESHOLD} rad/s "
              "against its start; peak = extreme reversed w_z")
    if "euler_disk" in scenes:
        print("effect, euler_disk: dE/dt = slope of a least-squares line through E(t) over the run")
    return 0


if __name__ == "__main__":
    sys.exit(main())
