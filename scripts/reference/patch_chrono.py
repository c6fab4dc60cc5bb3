#!/usr/bin/env python3
"""Applies the reference harness's three changes to an extracted Chrono 9.0.1 source tree.

usage: patch_chrono.py CHRONO_SRC_DIR

Each change is inserted at an anchor line and is idempotent (a marker comment is checked first).
Why each is needed: scripts/reference/build_chrono.sh.
"""
import shutil
import sys
from pathlib import Path

MARK = "vb-reference-harness"


def insert(path: Path, anchor: str, text: str, after: bool = True, count: int = 1) -> None:
    body = path.read_text()
    if MARK in body and text.strip() in body:
        return
    found = body.count(anchor)
    if found != count:
        sys.exit(f"patch_chrono: {path}: anchor {anchor.strip()!r} found {found} times, expected {count}")
    body = body.replace(anchor, anchor + text if after else text + anchor)
    path.write_text(body)


def main() -> None:
    if len(sys.argv) != 2:
        sys.exit("usage: patch_chrono.py CHRONO_SRC_DIR")
    src = Path(sys.argv[1])
    swig = src / "src/chrono_swig/interface/vehicle/ChModuleVehicle.i"
    insert(swig, '%include "../../../chrono_vehicle/ChVehicleVisualSystem.h"\n',
           f"// {MARK}: the class is abstract; SWIG 4.1 wraps a constructor without Irrlicht\n"
           "%ignore chrono::vehicle::ChVehicleVisualSystem::ChVehicleVisualSystem;\n", after=False)

    h = src / "src/chrono_vehicle/terrain/SCMTerrain.h"
    insert(h, "    void SetPlane(const ChCoordsys<>& plane);\n",
           f"\n    /// {MARK}: limit the grid to a box of the SCM plane (nodes outside are never ray-cast).\n"
           "    void SetBoundary(const ChAABB& aabb);\n")
    insert(h, "    ChCoordsys<> m_plane;",
           f"\n    bool m_boundary = false;  ///< {MARK}: grid limited to m_boundary_aabb?\n"
           "    ChAABB m_boundary_aabb;   ///< box in the SCM plane's frame\n",
           after=False)

    cpp = src / "src/chrono_vehicle/terrain/SCMTerrain.cpp"
    insert(cpp, "// Get the SCM reference plane.\n",
           f"// {MARK}: grid nodes outside the box (in the SCM plane's frame) are never ray-cast.\n"
           "void SCMTerrain::SetBoundary(const ChAABB& aabb) {\n"
           "    m_loader->m_boundary = true;\n"
           "    m_loader->m_boundary_aabb = aabb;\n"
           "}\n\n", after=False)
    insert(cpp, "            double y = ij.y() * m_delta;\n",
           f"            if (m_boundary && (x < m_boundary_aabb.min.x() || x > m_boundary_aabb.max.x() ||  // {MARK}\n"
           "                               y < m_boundary_aabb.min.y() || y > m_boundary_aabb.max.y()))\n"
           "                continue;\n", count=2)

    data = src / "data/vehicle/hmmwv"
    if not (data / "hmmwv_chassis.obj").exists():
        shutil.copyfile(data / "hmmwv_chassis_simple.obj", data / "hmmwv_chassis.obj")
    print("patch_chrono: applied")


if __name__ == "__main__":
    main()
