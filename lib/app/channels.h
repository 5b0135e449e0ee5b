#pragma once
// Channel names on the robot bus and the team bus: every daemon's defaults (options and config
// keys) come from here, so that what one daemon sends is what the next one listens to.
namespace slide::app::channels {

// Robot bus: sensor driver -> segmenter -> tracker -> optimizer, loop closer and peer sync.
inline constexpr char kScan[] = "SCAN";                   // lidar_scan_t
inline constexpr char kRgbd[] = "RGBD";                   // rgbd_frame_t
inline constexpr char kOdom[] = "ODOM";                   // odometry_t
inline constexpr char kSensorStatus[] = "SENSOR_STATUS";  // stream_status_t
inline constexpr char kInstances[] = "INSTANCES";         // frame_instances_t
// frame_instances_t: a thinned copy of INSTANCES (at most 200 points, 2 frames a second), what
// the viewer draws and the run logs keep.
inline constexpr char kInstancesPreview[] = "INSTANCES_PREVIEW";
inline constexpr char kKeyPoseBundle[] = "KEYPOSE_BUNDLE";  // keypose_bundle_t, own
inline constexpr char kPeerBundle[] = "PEER_BUNDLE";      // keypose_bundle_t, peers' (from peer sync)
inline constexpr char kLoopClosure[] = "LOOP_CLOSURE";    // loop_closure_t
inline constexpr char kObjectMap[] = "OBJECT_MAP";        // object_map_t, the merged map (own and merged peers' landmarks)
inline constexpr char kOwnMap[] = "OWN_MAP";              // object_map_t, the landmarks this robot observed itself
inline constexpr char kPeerMap[] = "PEER_MAP";            // object_map_t, peers' (from peer sync)
inline constexpr char kTrajectory[] = "TRAJECTORY";       // trajectory_t
inline constexpr char kOptimizerStatus[] = "OPTIMIZER_STATUS";
inline constexpr char kPeerSyncStatus[] = "PEER_SYNC_STATUS";
inline constexpr char kDaemonStatus[] = "DAEMON_STATUS";  // daemon_status_t (segmenter, tracker, loop closer)

// Team bus (peer sync only).
inline constexpr char kTeamHeartbeat[] = "TEAM_HEARTBEAT";
inline constexpr char kTeamChunk[] = "TEAM_CHUNK";
inline constexpr char kTeamAck[] = "TEAM_ACK";

}  // namespace slide::app::channels
