#!/usr/bin/python3
"""Writes ROS 1 bags with the layouts of real drivers (Debian's python3-rosbag), for the bag
reader's tests and benchmark.

The robot moves with known analytic motion: x = V t, yaw = W t (body frame base_link in odom).
A static world of points is measured from the pose at each point's own time, so a reader that
deskews from the per-point times recovers the world exactly.

  make_bags.py OUT_DIR [--os1-frames N]
writes OUT_DIR/ouster.bag   OS1-64 organised clouds (64 x 1024, per-point uint32 t in ns),
                            nav_msgs/Odometry at 100 Hz, /tf_static base_link -> os_sensor
       OUT_DIR/velodyne.bag VLP-16 unorganised clouds (float32 time, uint16 ring), odometry as
                            a /tf chain odom -> base_link at 10 Hz with a gap from 0.42 to 0.78 s
       OUT_DIR/livox.bag    Livox layout (float64 absolute timestamp in ns, uint8 line)
       OUT_DIR/rgbd.bag     RealSense-style colour (rgb8) + depth (16UC1) + CameraInfo, odometry
       OUT_DIR/rgbd32.bag   the same with bgr8 colour and 32FC1 depth
       OUT_DIR/rgbd_distorted.bag  rgbd.bag with a non-zero plumb_bob distortion in CameraInfo
       OUT_DIR/rgbd_yuv.bag the same with an unsupported colour encoding (yuv422)
       OUT_DIR/velodyne_bz2.bag, velodyne_lz4.bag  velodyne.bag with compressed chunks
       OUT_DIR/frames.bag   odometry of imu_link (0.2 m above base_link, /tf_static) at 100 Hz
                            and a moving joint imu_link -> gimbal on /tf (0 .. 0.5 s); small clouds
       OUT_DIR/broken.bag   small clouds on /points: message 1 cut short inside its data,
                            message 2 with fewer data bytes than its rows need
"""
import io
import math
import struct
import sys

import rosbag
import rospy
from geometry_msgs.msg import TransformStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import CameraInfo, Image, PointCloud2, PointField
from tf2_msgs.msg import TFMessage

V, W = 2.0, 0.5          # m/s forward, rad/s yaw
T0 = 1700000000.0        # bag start time (s, an epoch time like a real recording)
SENSOR_Z = 0.5           # os_sensor 0.5 m above base_link, no rotation
F32, F64, U8, U16, U32 = PointField.FLOAT32, PointField.FLOAT64, PointField.UINT8, PointField.UINT16, PointField.UINT32


def pose(t):
    """Body pose at time t (seconds after T0): x, y, yaw."""
    return V * t, 0.0, W * t


def world_point(row, col, rows, cols):
    """A static world point for beam row, column col: on a cylinder of radius 10 m around the start."""
    az = 2 * math.pi * col / cols
    el = math.radians(-15 + 30 * row / max(1, rows - 1))
    r = 10.0
    return r * math.cos(az), r * math.sin(az), SENSOR_Z + r * math.tan(el)


def to_sensor(p, t, sensor_z):
    """World point p seen from the sensor at time t (sensor = body + (0, 0, sensor_z))."""
    x, y, yaw = pose(t)
    dx, dy, dz = p[0] - x, p[1] - y, p[2] - sensor_z
    c, s = math.cos(yaw), math.sin(yaw)
    return c * dx + s * dy, -s * dx + c * dy, dz


def stamp(t):
    return rospy.Time.from_sec(T0 + t)


def cloud(t, frame, fields, point_step, rows, cols, pack, sweep=0.1):
    msg = PointCloud2()
    msg.header.stamp = stamp(t)
    msg.header.frame_id = frame
    msg.height, msg.width = rows, cols
    msg.fields = [PointField(name=n, offset=o, datatype=d, count=1) for n, o, d in fields]
    msg.is_bigendian = False
    msg.point_step = point_step
    msg.row_step = point_step * cols
    buf = bytearray(msg.row_step * rows)
    for r in range(rows):
        for c in range(cols):
            dt = sweep * c / cols   # columns fire in order over the sweep
            p = to_sensor(world_point(r, c, rows, cols), t + dt, SENSOR_Z)
            pack(buf, (r * cols + c) * point_step, p, r, c, dt, t)
    msg.data = bytes(buf)
    msg.is_dense = False
    return msg


def ouster_pack(buf, off, p, r, c, dt, t):
    if r == 3 and c % 100 == 0:   # no return: Ouster writes zeros
        p = (0.0, 0.0, 0.0)
    if r == 5 and c % 128 == 0:   # a NaN point
        p = (float("nan"), 0.0, 0.0)
    struct.pack_into("<fff4xfIHHHxxI", buf, off, p[0], p[1], p[2], 100.0 + r, int(round(dt * 1e9)), 7, r, 3, 1000)


OUSTER_FIELDS = [("x", 0, F32), ("y", 4, F32), ("z", 8, F32), ("intensity", 16, F32), ("t", 20, U32),
                 ("reflectivity", 24, U16), ("ring", 26, U16), ("ambient", 28, U16), ("range", 32, U32)]


def velodyne_pack(buf, off, p, r, c, dt, t):
    struct.pack_into("<fff4xfHxxf", buf, off, p[0], p[1], p[2], float(c % 256), r, dt - 0.1)


VELODYNE_FIELDS = [("x", 0, F32), ("y", 4, F32), ("z", 8, F32), ("intensity", 16, F32), ("ring", 20, U16),
                   ("time", 24, F32)]


def livox_pack(buf, off, p, r, c, dt, t):
    struct.pack_into("<ffffBBd", buf, off, p[0], p[1], p[2], 50.0, 0, r, (T0 + t + dt) * 1e9)


LIVOX_FIELDS = [("x", 0, F32), ("y", 4, F32), ("z", 8, F32), ("intensity", 12, F32), ("tag", 16, U8), ("line", 17, U8),
                ("timestamp", 18, F64)]


def quat_yaw(yaw):
    return 0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)


def odometry(t):
    m = Odometry()
    m.header.stamp = stamp(t)
    m.header.frame_id = "odom"
    m.child_frame_id = "base_link"
    x, y, yaw = pose(t)
    m.pose.pose.position.x, m.pose.pose.position.y = x, y
    q = quat_yaw(yaw)
    m.pose.pose.orientation.x, m.pose.pose.orientation.y, m.pose.pose.orientation.z, m.pose.pose.orientation.w = q
    return m


def transform(t, parent, child, x, y, z, yaw):
    m = TransformStamped()
    m.header.stamp = stamp(t)
    m.header.frame_id = parent
    m.child_frame_id = child
    m.transform.translation.x, m.transform.translation.y, m.transform.translation.z = x, y, z
    q = quat_yaw(yaw)
    m.transform.rotation.x, m.transform.rotation.y, m.transform.rotation.z, m.transform.rotation.w = q
    return m


def write_static(bag, child, z, t=0.0):
    bag.write("/tf_static", TFMessage(transforms=[transform(t, "base_link", child, 0, 0, z, 0)]), stamp(t))


def odom_100hz(bag, t_end):
    for k in range(int(t_end * 100) + 1):
        t = 0.01 * k
        bag.write("/odom", odometry(t), stamp(t))


def ouster_bag(path, frames):
    with rosbag.Bag(path, "w") as bag:
        write_static(bag, "os_sensor", SENSOR_Z)
        odom_100hz(bag, 0.1 * frames + 0.1)
        for i in range(frames):
            t = 0.1 * i + 0.05
            bag.write("/os_cloud_node/points", cloud(t, "os_sensor", OUSTER_FIELDS, 48, 64, 1024, ouster_pack),
                      stamp(t + 0.1))


def velodyne_bag(path, compression="none"):
    with rosbag.Bag(path, "w", compression=compression) as bag:
        write_static(bag, "velodyne", SENSOR_Z)
        for k in range(11):   # /tf odom -> base_link at 10 Hz, 0.0 .. 1.0 s, without 0.5 .. 0.7
            t = 0.1 * k
            if 0.45 < t < 0.75:
                continue
            x, y, yaw = pose(t)
            bag.write("/tf", TFMessage(transforms=[transform(t, "odom", "base_link", x, y, 0, yaw)]), stamp(t))
        for i in range(10):   # frames at 0.15 .. 1.05 s; stamps at the sweep's end (time is negative)
            t = 0.1 * i + 0.05
            m = cloud(t, "velodyne", VELODYNE_FIELDS, 32, 1, 16 * 450,
                      lambda b, o, p, r, c, dt, t0: velodyne_pack(b, o, p, c % 16, c, dt, t0))
            m.header.stamp = stamp(t + 0.1)
            bag.write("/velodyne_points", m, stamp(t + 0.1))


def livox_bag(path):
    with rosbag.Bag(path, "w") as bag:
        odom_100hz(bag, 1.0)
        for i in range(3):
            t = 0.1 * i + 0.1
            bag.write("/livox/lidar", cloud(t, "base_link", LIVOX_FIELDS, 26, 1, 6 * 400,
                                            lambda b, o, p, r, c, dt, t0: livox_pack(b, o, p, c % 6, c, dt, t0)), stamp(t))


def rgbd_bag(path, color_enc, depth_enc, w=64, h=48, distortion=(0.0,) * 5):
    with rosbag.Bag(path, "w") as bag:
        bag.write("/tf_static", TFMessage(transforms=[
            transform(0, "base_link", "camera_link", 0.1, 0, 0.3, 0),
            optical(0)]), stamp(0))
        odom_100hz(bag, 1.0)
        for i in range(5):
            t = 0.1 + 0.15 * i
            info = CameraInfo()
            info.header.stamp, info.header.frame_id = stamp(t), "camera_color_optical_frame"
            info.width, info.height = w, h
            info.distortion_model = "plumb_bob"
            info.D = list(distortion)
            info.K = [50.0, 0, 32.0, 0, 51.0, 24.0, 0, 0, 1]
            bag.write("/camera/color/camera_info", info, stamp(t))
            col = Image(height=h, width=w, encoding=color_enc, is_bigendian=0, step=w * 3 + 4)
            col.header.stamp, col.header.frame_id = stamp(t), "camera_color_optical_frame"
            data = bytearray(col.step * h)
            for y in range(h):
                for x in range(w):
                    data[y * col.step + 3 * x: y * col.step + 3 * x + 3] = bytes((10, 20 + i, 30))  # in encoding order
            col.data = bytes(data)
            bag.write("/camera/color/image_raw", col, stamp(t))
            bpp = 2 if depth_enc == "16UC1" else 4
            dep = Image(height=h, width=w, encoding=depth_enc, is_bigendian=0, step=w * bpp)
            dep.header.stamp, dep.header.frame_id = stamp(t + 0.005), "camera_color_optical_frame"
            d = bytearray(dep.step * h)
            for y in range(h):
                for x in range(w):
                    metres = 1.0 + 0.01 * x
                    if x == 0:
                        metres = float("nan") if bpp == 4 else 0.0
                    if bpp == 2:
                        struct.pack_into("<H", d, y * dep.step + 2 * x, int(round(metres * 1000)))
                    else:
                        struct.pack_into("<f", d, y * dep.step + 4 * x, metres)
            dep.data = bytes(d)
            bag.write("/camera/aligned_depth_to_color/image_raw", dep, stamp(t + 0.005))


def small_cloud(t, frame, n=100):
    """n points on the cylinder, seen from the body at time t (no per-point time)."""
    return cloud(t, frame, [("x", 0, F32), ("y", 4, F32), ("z", 8, F32)], 12, 1, n,
                 lambda b, o, p, r, c, dt, t0: struct.pack_into("<fff", b, o, *p), sweep=0.0)


def odometry_of(t, child, x, y, z, yaw):
    m = odometry(t)
    m.child_frame_id = child
    m.pose.pose.position.x, m.pose.pose.position.y, m.pose.pose.position.z = x, y, z
    return m


def frames_bag(path):
    """Odometry of imu_link (z 0.2 above base_link, same heading); gimbal x 0.1 ahead of imu_link, yaw 0.3 t."""
    with rosbag.Bag(path, "w") as bag:
        bag.write("/tf_static", TFMessage(transforms=[transform(0, "base_link", "imu_link", 0, 0, 0.2, 0)]), stamp(0))
        for k in range(101):
            t = 0.01 * k
            x, y, yaw = pose(t)
            bag.write("/odom", odometry_of(t, "imu_link", x, y, 0.2, yaw), stamp(t))
        for k in range(6):
            t = 0.1 * k
            bag.write("/tf", TFMessage(transforms=[transform(t, "imu_link", "gimbal", 0.1, 0, 0, 0.3 * t)]), stamp(t))
        for i in range(9):
            t = 0.1 * i + 0.05
            bag.write("/points", small_cloud(t, "base_link"), stamp(t))


def broken_bag(path):
    with rosbag.Bag(path, "w") as bag:
        odom_100hz(bag, 1.0)
        for i in range(4):
            t = 0.1 * i + 0.1
            m = small_cloud(t, "base_link")
            if i == 2:
                m.data = m.data[:len(m.data) // 2]
            buf = io.BytesIO()
            m.serialize(buf)
            raw = buf.getvalue()
            if i == 1:
                raw = raw[:-50]
            bag.write("/points", (m._type, raw, m._md5sum, 0, PointCloud2), stamp(t), raw=True)


def optical(t):
    """camera_link -> camera_color_optical_frame: the usual optical rotation (z forward, x right, y down)."""
    m = TransformStamped()
    m.header.stamp = stamp(t)
    m.header.frame_id = "camera_link"
    m.child_frame_id = "camera_color_optical_frame"
    m.transform.rotation.x, m.transform.rotation.y, m.transform.rotation.z, m.transform.rotation.w = -0.5, 0.5, -0.5, 0.5
    return m


def main():
    if len(sys.argv) < 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(sys.argv) >= 2 else 2
    out = sys.argv[1]
    frames = 3
    if "--os1-frames" in sys.argv:
        frames = int(sys.argv[sys.argv.index("--os1-frames") + 1])
    only = sys.argv[sys.argv.index("--only") + 1] if "--only" in sys.argv else None
    jobs = {"ouster": lambda: ouster_bag(out + "/ouster.bag", frames),
            "velodyne": lambda: velodyne_bag(out + "/velodyne.bag"),
            "livox": lambda: livox_bag(out + "/livox.bag"),
            "rgbd": lambda: rgbd_bag(out + "/rgbd.bag", "rgb8", "16UC1"),
            "rgbd32": lambda: rgbd_bag(out + "/rgbd32.bag", "bgr8", "32FC1"),
            "rgbd_distorted": lambda: rgbd_bag(out + "/rgbd_distorted.bag", "rgb8", "16UC1",
                                               distortion=(0.1, -0.05, 0.001, 0.0, 0.0)),
            "rgbd_yuv": lambda: rgbd_bag(out + "/rgbd_yuv.bag", "yuv422", "16UC1"),
            "velodyne_bz2": lambda: velodyne_bag(out + "/velodyne_bz2.bag", "bz2"),
            "velodyne_lz4": lambda: velodyne_bag(out + "/velodyne_lz4.bag", "lz4"),
            "frames": lambda: frames_bag(out + "/frames.bag"),
            "broken": lambda: broken_bag(out + "/broken.bag")}
    for name, job in jobs.items():
        if only is None or only == name:
            job()
    return 0


if __name__ == "__main__":
    sys.exit(main())
