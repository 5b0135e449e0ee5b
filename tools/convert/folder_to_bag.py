#!/usr/bin/python3
"""Writes a robot's KITTI-layout LiDAR folder (velodyne/*.bin, times.txt, odom.txt) as a ROS 1 bag
(python3-rosbag): /points (sensor_msgs/PointCloud2 x y z intensity, frame base_link) and /odom
(nav_msgs/Odometry, odom -> base_link) at the folder's times.

  folder_to_bag.py FOLDER OUT.bag [--t0 SECONDS]
--t0 is added to every time (default 1700000000: bags carry epoch times).
"""
import os
import struct
import sys

import rosbag
import rospy
from nav_msgs.msg import Odometry
from sensor_msgs.msg import PointCloud2, PointField


def main():
    args = sys.argv[1:]
    if len(args) < 2 or args[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if args and args[0] in ("-h", "--help") else 2
    folder, out = args[0], args[1]
    t0 = float(args[args.index("--t0") + 1]) if "--t0" in args else 1700000000.0
    times = [float(l) for l in open(os.path.join(folder, "times.txt")) if l.strip()]
    scans = sorted(f for f in os.listdir(os.path.join(folder, "velodyne")) if f.endswith(".bin"))
    if len(times) != len(scans):
        sys.exit(f"{folder}: {len(times)} times for {len(scans)} scans")
    odom = [l.split() for l in open(os.path.join(folder, "odom.txt")) if l.strip() and not l.startswith("#")]
    with rosbag.Bag(out, "w") as bag:
        for row in odom:
            t, x, y, z, qx, qy, qz, qw = map(float, row)
            m = Odometry()
            m.header.stamp = rospy.Time.from_sec(t0 + t)
            m.header.frame_id, m.child_frame_id = "odom", "base_link"
            p, q = m.pose.pose.position, m.pose.pose.orientation
            p.x, p.y, p.z, q.x, q.y, q.z, q.w = x, y, z, qx, qy, qz, qw
            bag.write("/odom", m, m.header.stamp)
        for t, name in zip(times, scans):
            data = open(os.path.join(folder, "velodyne", name), "rb").read()
            m = PointCloud2()
            m.header.stamp = rospy.Time.from_sec(t0 + t)
            m.header.frame_id = "base_link"
            m.height, m.width = 1, len(data) // 16
            m.fields = [PointField(name=n, offset=4 * i, datatype=PointField.FLOAT32, count=1)
                        for i, n in enumerate(("x", "y", "z", "intensity"))]
            m.is_bigendian, m.point_step, m.row_step, m.is_dense = False, 16, 16 * m.width, True
            m.data = data[:16 * m.width]
            bag.write("/points", m, m.header.stamp)
    print(f"{out}: {len(scans)} scans, {len(odom)} odometry poses")
    return 0


if __name__ == "__main__":
    sys.exit(main())
