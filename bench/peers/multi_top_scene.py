#!/usr/bin/python3
"""Writes a scene of N Tippe-Tops for `simulate`: OUT_DIR/tippe_tops_N.urdf and .yaml (N independent
tops), or with --crowd OUT_DIR/tippe_crowd_N.urdf and .yaml (N tops in a walled arena).

    bench/peers/multi_top_scene.py N OUT_DIR [--crowd]

Each top is the one of urdf/tippe_top.urdf (same mass, inertia, spheres, friction, restitution)
on a floating joint under a massless root link "world", as urdf/tippe_top_duel.urdf does; the
starts are those of StartOf() in bench/peers/tippe_top_scene.h (top 0 = config/tippe_top.yaml,
the others with varied tilt, tilt direction and spin, on a grid 5 m apart), so that the peer
engines and `simulate` run the same N tops. The crowd (CrowdStartOf(), CrowdWalls()): the same
tilts and spins on a grid 45 mm apart centred on the origin, each top moving at 0.1-0.3 m/s, in
the square |x|, |y| <= columns * 45 mm / 2 bounded by four wall planes (`<plane/>` colliders of
the world link, docs/urdf.md), so that the tops hit each other and the walls. Prints the two paths.
"""
import math
import os
import sys

# urdf/tippe_top.urdf (and bench/peers/tippe_top_scene.h)
MASS, A, C = 6e-3, 8e-7, 7e-7
R1, A1, R2, A2 = 0.015, 0.003, 0.005, 0.016
MU, PATCH_RADIUS = 0.3, 5e-4
THETA0, SPIN0 = 0.1, 180.0
SPACING = 5.0
GOLDEN_ANGLE = 2.399963229728653
# the crowd (kCrowdSpacing, kTouchGap of tippe_top_scene.h)
CROWD_SPACING = 0.045
TOUCH_GAP = 1e-5


def start_of(i, n):
    """(position, quaternion x y z w, spin about e3): StartOf() of tippe_top_scene.h."""
    if i == 0:
        theta0, azimuth, spin = THETA0, 0.0, SPIN0
    else:
        theta0 = 0.05 + 0.05 * (i % 4)
        azimuth = GOLDEN_ANGLE * i
        spin = (150.0 + 10.0 * (i % 7)) * (1.0 if (i // 7) % 2 == 0 else -1.0)
    columns = int(math.ceil(math.sqrt(n)))
    pos = (SPACING * (i % columns), SPACING * (i // columns), R1 - A1 * math.cos(theta0))
    h = 0.5 * theta0
    quat = (math.sin(h) * math.cos(azimuth), math.sin(h) * math.sin(azimuth), 0.0, math.cos(h))
    return pos, quat, spin


def columns_of(n):
    return int(math.ceil(math.sqrt(n)))


def crowd_half_width(n):
    return 0.5 * CROWD_SPACING * columns_of(n)


def crowd_start_of(i, n):
    """(position, quaternion x y z w, spin about e3, velocity): CrowdStartOf() of tippe_top_scene.h."""
    _, quat, spin = start_of(i, n)
    theta0 = THETA0 if i == 0 else 0.05 + 0.05 * (i % 4)
    columns = columns_of(n)
    pos = (CROWD_SPACING * ((i % columns) - 0.5 * (columns - 1)),
           CROWD_SPACING * ((i // columns) - 0.5 * (columns - 1)), R1 - A1 * math.cos(theta0))
    speed = 0.1 + 0.1 * (i % 3)
    heading = 1.3 + GOLDEN_ANGLE * i
    return pos, quat, spin, (speed * math.cos(heading), speed * math.sin(heading), 0.0)


def crowd_walls(n):
    """(name, inward normal, d) of the planes n . x = d: CrowdWalls() of tippe_top_scene.h."""
    l = crowd_half_width(n)
    return [("wall_x_minus", (1.0, 0.0, 0.0), -l), ("wall_x_plus", (-1.0, 0.0, 0.0), -l),
            ("wall_y_minus", (0.0, 1.0, 0.0), -l), ("wall_y_plus", (0.0, -1.0, 0.0), -l)]


# the rpy that turns a frame's z axis into each wall's normal (docs/urdf.md: a <plane/> is the
# half-space below its collision frame's xy plane): about y by ±pi/2 for ±x, about x by ∓pi/2 for ±y
WALL_RPY = {(1.0, 0.0, 0.0): (0.0, math.pi / 2, 0.0), (-1.0, 0.0, 0.0): (0.0, -math.pi / 2, 0.0),
            (0.0, 1.0, 0.0): (-math.pi / 2, 0.0, 0.0), (0.0, -1.0, 0.0): (math.pi / 2, 0.0, 0.0)}


def world_link(n, crowd):
    if not crowd:
        return '  <link name="world"/>\n'
    l = crowd_half_width(n)
    out = ['  <link name="world">  <!-- no inertial: the static world; the arena\'s four walls -->\n']
    for name, normal, d in crowd_walls(n):
        xyz = tuple(d * c for c in normal)
        rpy = WALL_RPY[normal]
        out.append(f'    <collision name="{name}">\n'
                   f'      <origin xyz="{xyz[0]!r} {xyz[1]!r} {xyz[2]!r}" rpy="{rpy[0]!r} {rpy[1]!r} {rpy[2]!r}"/>\n'
                   f'      <geometry><box size="{2 * l!r} {2 * l!r} 0.001"/></geometry>\n'
                   '    </collision>\n')
    out.append('  </link>\n  <nonsmooth_sim reference="world">\n')
    for name, _, _ in crowd_walls(n):
        out.append(f'    <collision name="{name}"><plane/></collision>\n')
    out.append('  </nonsmooth_sim>\n')
    # the walls' own law: mu = 1, no drilling, as the peers' walls; the pair rule (mu = min,
    # R̄ = max, restitution = max) gives the tops' mu = 0.3 and R̄ against them
    out.append('  <gazebo reference="world">\n    <collision>\n      <surface>\n        <friction>\n'
               '          <ode><mu>1.0</mu><mu2>1.0</mu2></ode>\n'
               '          <torsional><coefficient>1.0</coefficient><patch_radius>0.0</patch_radius></torsional>\n'
               '        </friction>\n      </surface>\n    </collision>\n  </gazebo>\n')
    return "".join(out)


def link(i, pos):
    name = f"top{i}"
    return f"""  <joint name="{name}_joint" type="floating">
    <parent link="world"/>
    <child link="{name}"/>
    <origin xyz="{pos[0]!r} {pos[1]!r} {pos[2]!r}" rpy="0 0 0"/>
  </joint>
  <link name="{name}">
    <inertial>
      <origin xyz="0 0 0" rpy="0 0 0"/>
      <mass value="{MASS!r}"/>
      <inertia ixx="{A!r}" ixy="0" ixz="0" iyy="{A!r}" iyz="0" izz="{C!r}"/>
    </inertial>
    <collision name="{name}_big_sphere">
      <origin xyz="0 0 {A1!r}" rpy="0 0 0"/>
      <geometry><sphere radius="{R1!r}"/></geometry>
    </collision>
    <collision name="{name}_peg_sphere">
      <origin xyz="0 0 {A2!r}" rpy="0 0 0"/>
      <geometry><sphere radius="{R2!r}"/></geometry>
    </collision>
  </link>
  <gazebo reference="{name}">
    <collision>
      <surface>
        <friction>
          <ode><mu>{MU!r}</mu><mu2>{MU!r}</mu2></ode>
          <torsional>
            <coefficient>{MU!r}</coefficient>
            <use_patch_radius>true</use_patch_radius>
            <patch_radius>{PATCH_RADIUS!r}</patch_radius>
          </torsional>
        </friction>
      </surface>
    </collision>
  </gazebo>
  <nonsmooth_sim reference="{name}"><restitution>0.0</restitution></nonsmooth_sim>
"""


def scene_paths(n, out_dir, crowd=False):
    base = os.path.join(out_dir, f"tippe_{'crowd' if crowd else 'tops'}_{n}")
    return base + ".urdf", base + ".yaml"


def main():
    argv = sys.argv[1:]
    crowd = "--crowd" in argv
    argv = [a for a in argv if a != "--crowd"]
    if len(argv) != 2 or not argv[0].isdigit() or int(argv[0]) < 1:
        sys.exit("usage: " + __doc__.strip().splitlines()[3].strip())
    n, out_dir = int(argv[0]), argv[1]
    os.makedirs(out_dir, exist_ok=True)
    if crowd:
        starts = [crowd_start_of(i, n) for i in range(n)]
        rule = "CrowdStartOf()"
        what = f"{n} Tippe-Tops of urdf/tippe_top.urdf in a walled arena"
    else:
        starts = [start_of(i, n) + ((0.0, 0.0, 0.0),) for i in range(n)]
        rule = "StartOf()"
        what = f"{n} Tippe-Tops of urdf/tippe_top.urdf"
    urdf, yaml = scene_paths(n, out_dir, crowd)
    name = os.path.splitext(os.path.basename(urdf))[0]
    with open(urdf, "w") as f:
        f.write('<?xml version="1.0"?>\n')
        f.write(f"<!-- {what}, written by bench/peers/multi_top_scene.py -->\n")
        f.write(f'<robot name="{name}">\n')
        f.write(world_link(n, crowd))
        for i, start in enumerate(starts):
            f.write(link(i, start[0]))
        f.write("</robot>\n")
    with open(yaml, "w") as f:
        f.write(f"# starts of the {n} tops of {os.path.basename(urdf)} ({rule} of "
                "bench/peers/tippe_top_scene.h)\nbodies:\n")
        for i, (pos, quat, spin, vel) in enumerate(starts):
            f.write(f"  top{i}:\n"
                    f"    position: [{pos[0]!r}, {pos[1]!r}, {pos[2]!r}]\n"
                    f"    orientation: [{quat[0]!r}, {quat[1]!r}, {quat[2]!r}, {quat[3]!r}]\n"
                    f"    linear_velocity: [{vel[0]!r}, {vel[1]!r}, {vel[2]!r}]\n"
                    f"    angular_velocity: [0.0, 0.0, {spin!r}]\n")
    print(urdf)
    print(yaml)


if __name__ == "__main__":
    main()
