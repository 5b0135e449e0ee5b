#include "mapped_robot/map_robot.h"

#include <memory>

#include "backend/optimizer.h"
#include "clock/thread_cpu.h"
#include "emulator/rgbd_emulator.h"
#include "frontend/labelled_segmenter.h"
#include "simulator/dataset_writer.h"
#include "simulator/lidar.h"
#include "simulator/ray_caster.h"

namespace slide::mapped_robot {

namespace {
double cpuS() { return clock::threadCpuMs() * 1e-3; }
}  // namespace

RobotMapping mapRobot(const simulator::Scenario& sc, int robot, const SensorRig& rig, const MappingSetup& setup) {
  const simulator::RobotRun& run = sc.robots.at(static_cast<std::size_t>(robot));
  const bool lidar = rig.kind == SensorRig::Kind::Lidar;
  const simulator::LidarModel lidar_model = lidar ? simulator::lidarModel(rig.model) : simulator::LidarModel{};
  const simulator::CameraModel camera = lidar ? simulator::CameraModel{} : simulator::cameraModel(rig.model);
  const frontend::LabelledSegmenter segmenter(setup.classes, setup.frontend.labelled);
  frontend::KeyPoseBundler bundler(frontend::Tracker(setup.classes, setup.frontend.tracker, setup.frontend.fit),
                                   setup.frontend.keypose);
  backend::Optimizer optimizer(setup.backend, setup.classes, run.id);

  bool any_moving = false;
  for (const auto& o : sc.world.objects) any_moving |= o.moving();
  std::unique_ptr<simulator::RayCaster> caster;
  RobotMapping out;
  for (std::size_t k = 0; k < run.ground_truth.size(); ++k) {
    const double t = run.ground_truth.times[k];
    const double c0 = cpuS();
    if (!caster || any_moving) caster = std::make_unique<simulator::RayCaster>(sc.world, t);
    const Pose T_world_sensor = run.ground_truth.poses[k] * rig.T_body_sensor;
    std::mt19937_64 rng = simulator::frameRng(setup.seed, run.id, static_cast<int>(k));
    io::LabelledScan scan;
    frontend::RgbdFrame frame;
    if (lidar) {
      scan = simulator::simulateLidarScan(*caster, T_world_sensor, lidar_model, rng);
      if (setup.emulator)
        scan = emulator::emulateLidarLabels(
            scan, setup.emulator->lidar,
            emulator::detectionSeed(setup.emulator->seed ^ setup.seed, run.id, static_cast<int>(k)));
      out.raw_points += static_cast<long>(scan.size());
    } else {
      const simulator::RgbdImage img = simulator::renderRgbd(*caster, T_world_sensor, camera, rng);
      frame = rgbdFrameOf(img, camera);
      if (setup.emulator) {
        io::InstanceMask truth;
        truth.mask = img.instance;
        truth.class_id = img.instance_class;
        const emulator::EmulatedMasks e = emulator::emulateRgbdDetections(
            truth, img.depth, 0.001, setup.emulator->rgbd,
            emulator::detectionSeed(setup.emulator->seed ^ setup.seed, run.id, static_cast<int>(k)));
        frame.mask.assign(e.masks.mask.begin<std::uint16_t>(), e.masks.mask.end<std::uint16_t>());
        frame.instance_class = e.masks.class_id;
        frame.instance_confidence = e.confidence;
      }
      for (auto d : frame.depth) out.raw_points += d > 0;
    }
    const double c1 = cpuS();
    frontend::InputIssues issues;
    frontend::FrameInstances fi;
    fi.utime = static_cast<std::int64_t>(t * 1e6);
    fi.odom_pose = run.odometry[k];
    fi.instances = lidar ? segmenter.segment(scan, issues)
                         : frontend::segmentRgbd(frame, setup.classes, setup.frontend.rgbd, issues);
    for (frontend::Instance& in : fi.instances) in.points = frontend::transformCloud(rig.T_body_sensor, in.points);
    auto bundle = bundler.process(fi, issues);
    out.input_issues += issues.total();
    const double c2 = cpuS();
    if (bundle) {
      bundle->robot = run.id;
      const backend::UpdateResult u = optimizer.addBundle(*bundle);
      out.rejected_bundles += !u.accepted;
    }
    out.sim_cpu_s += c1 - c0;
    out.frontend_cpu_s += c2 - c1;
    out.backend_cpu_s += cpuS() - c2;
    ++out.frames;
  }
  const double c3 = cpuS();
  optimizer.fullSolve();
  out.objects = optimizer.landmarks(true);
  out.backend_cpu_s += cpuS() - c3;
  out.keyposes = optimizer.numKeyPoses();
  return out;
}

}  // namespace slide::mapped_robot
