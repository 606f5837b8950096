#pragma once
// rollbench score --peers: the solves of another program (a "peer", e.g.
// analysis/peers/scipy_peer.py), listed in a peer file (docs/formats.md,
// "Peer runs") with their trajectories, timings and counts, turned into runs
// of a report, so that they appear in the same tables and work–precision
// figures as the suite's own methods.
#include <nlohmann/json.hpp>
#include <string>

namespace rb {

inline constexpr const char* kPeersSchema = "rollbench.peers/1";

// Scores every run of the peer file at peers_path (trajectories relative to
// its folder) against the suite's reference and returns a report: into's
// (a report of `rollbench run` on the same scenes, t_end and output grid)
// with the peer's runs appended and the tolerance fits refitted, or, with
// into empty, a report of the peer's runs alone. Throws InputError naming
// the file and the key for a malformed peer file, a trajectory that does not
// fit the grid, or a report of other scenes, end times or grid.
nlohmann::json score_peers(const std::string& peers_path, const std::string& into, const std::string& cache_dir);

}  // namespace rb
