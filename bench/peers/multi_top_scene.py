#!/usr/bin/python3
"""Writes a scene of N independent Tippe-Tops for `simulate`: OUT_DIR/tippe_tops_N.urdf and .yaml.

    bench/peers/multi_top_scene.py N OUT_DIR

Each top is the one of urdf/tippe_top.urdf (same mass, inertia, spheres, friction, restitution)
on a floating joint under a massless root link "world", as urdf/tippe_top_duel.urdf does; the
starts are those of StartOf() in bench/peers/tippe_top_scene.h (top 0 = config/tippe_top.yaml,
the others with varied tilt, tilt direction and spin, on a grid 5 m apart), so that the peer
engines and `simulate` run the same N tops. Prints the two paths.
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


def main():
    if len(sys.argv) != 3 or not sys.argv[1].isdigit() or int(sys.argv[1]) < 1:
        sys.exit(__doc__.strip().splitlines()[2].strip())
    n, out_dir = int(sys.argv[1]), sys.argv[2]
    os.makedirs(out_dir, exist_ok=True)
    starts = [start_of(i, n) for i in range(n)]
    urdf = os.path.join(out_dir, f"tippe_tops_{n}.urdf")
    yaml = os.path.join(out_dir, f"tippe_tops_{n}.yaml")
    with open(urdf, "w") as f:
        f.write('<?xml version="1.0"?>\n')
        f.write(f"<!-- {n} Tippe-Tops of urdf/tippe_top.urdf, written by "
                "bench/peers/multi_top_scene.py -->\n")
        f.write(f'<robot name="tippe_tops_{n}">\n  <link name="world"/>\n')
        for i, (pos, _, _) in enumerate(starts):
            f.write(link(i, pos))
        f.write("</robot>\n")
    with open(yaml, "w") as f:
        f.write(f"# starts of the {n} tops of {os.path.basename(urdf)} (StartOf() of "
                "bench/peers/tippe_top_scene.h)\nbodies:\n")
        for i, (pos, quat, spin) in enumerate(starts):
            f.write(f"  top{i}:\n"
                    f"    position: [{pos[0]!r}, {pos[1]!r}, {pos[2]!r}]\n"
                    f"    orientation: [{quat[0]!r}, {quat[1]!r}, {quat[2]!r}, {quat[3]!r}]\n"
                    "    linear_velocity: [0.0, 0.0, 0.0]\n"
                    f"    angular_velocity: [0.0, 0.0, {spin!r}]\n")
    print(urdf)
    print(yaml)


if __name__ == "__main__":
    main()
