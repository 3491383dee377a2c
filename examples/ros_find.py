#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Asks a running lmk_node to find a landmark in the robot's latest frame, with rospy, and prints
each match: its landmark, rank, error and box centre in the frame the answer names.

    python3 examples/ros_find.py [NAME] [--json]

Empty NAME: every landmark. With PYTHONPATH=build/ros/python and ROS_PACKAGE_PATH=ros/msg from a
build tree (docs/ros.md, "From Python and the shell"); --json prints the matches as JSON."""

import json
import sys

import rospy
from lmk_msgs.srv import FindLandmark


def main(argv):
    as_json = "--json" in argv
    names = [a for a in argv[1:] if a != "--json"]
    rospy.init_node("lmk_find_example", anonymous=True)
    rospy.wait_for_service("/lmk_node/find_landmark", timeout=30)
    find = rospy.ServiceProxy("/lmk_node/find_landmark", FindLandmark)
    answer = find(name=names[0] if names else "")
    if not answer.success:
        sys.exit(f"lmk_node: {answer.message}")
    matches = [{"landmark": m.landmark, "rank": m.rank, "error": m.error,
                "position": [m.box_pose.position.x, m.box_pose.position.y,
                             m.box_pose.position.z]} for m in answer.matches]
    if as_json:
        print(json.dumps({"frame": answer.header.frame_id, "matches": matches}))
        return
    print(f"{answer.message} (in {answer.header.frame_id})")
    for m in matches:
        x, y, z = m["position"]
        print(f"  {m['landmark']} #{m['rank']}: error {1000 * m['error']:.1f} mm, "
              f"at {x:.3f} {y:.3f} {z:.3f} m")


if __name__ == "__main__":
    main(sys.argv)
