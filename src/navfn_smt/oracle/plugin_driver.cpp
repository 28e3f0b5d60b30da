// navfn-smt: the oracle's driver around Nav2's planner plugin, compiled with navfn_planner.cpp,
// navfn.cpp, costmap_2d.cpp (and parameter_handler.cpp where the version has it) as they are.
//
// One process serves many requests on stdin, answers on stdout (little-endian, native ints):
//   request:  int32 size_x, size_y, ncases; float64 origin_x, origin_y, resolution, tolerance;
//             int32 use_astar, allow_unknown, max_cycles_factor, use_final_approach_orientation;
//             size_x*size_y cost bytes (the master costmap, index my * size_x + mx);
//             ncases x float64[12] (start x, y, qx, qy, qz, qw; goal x, y, qx, qy, qz, qw)
//   answer per case: int32 outcome, npose, nlog, msglen; char message[msglen];
//             float64 poses[npose][6] (x, y, qx, qy, qz, qw); per log line: int32 level, len;
//             char line[len]
//   after the request's cases: float64 seconds spent in createPlan, summed
// outcome: 0 createPlan returned (the path may be empty), 1 StartOutsideMapBounds,
// 2 GoalOutsideMapBounds, 3 GoalOccupied, 4 NoValidPathCouldBeFound, 5 another exception.
// A request with size_x == 0 ends the process.
//
// Each request configures a new NavfnPlanner on a node whose parameter overrides are the
// request's (as a params file gives them; a version that does not declare max_cycles_factor
// never reads it).  Each case starts from the request's costs (clearRobotCell changes the
// costmap, and Nav2's costmap would be refreshed between plans), and its log from empty.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "nav2_navfn_planner/navfn_planner.hpp"
#if NAVFN_SMT_PLUGIN_API >= 2
#include "nav2_core/planner_exceptions.hpp"
#endif

#include "navfn_smt/node_types.hpp"

static bool read_all(void * p, size_t n) {return fread(p, 1, n, stdin) == n;}
static void write_all(const void * p, size_t n) {fwrite(p, 1, n, stdout);}
static void write_i32(int32_t v) {write_all(&v, 4);}

static int outcome_of(const std::exception & e)
{
#if NAVFN_SMT_PLUGIN_API >= 2
  if (dynamic_cast<const nav2_core::StartOutsideMapBounds *>(&e)) {return 1;}
  if (dynamic_cast<const nav2_core::GoalOutsideMapBounds *>(&e)) {return 2;}
  if (dynamic_cast<const nav2_core::GoalOccupied *>(&e)) {return 3;}
  if (dynamic_cast<const nav2_core::NoValidPathCouldBeFound *>(&e)) {return 4;}
#else
  (void)e;
#endif
  return 5;
}

static geometry_msgs::msg::PoseStamped pose_of(const double * v)
{
  geometry_msgs::msg::PoseStamped p;
  p.header.frame_id = "map";
  p.pose.position.x = v[0];
  p.pose.position.y = v[1];
  p.pose.orientation.x = v[2];
  p.pose.orientation.y = v[3];
  p.pose.orientation.z = v[4];
  p.pose.orientation.w = v[5];
  return p;
}

static nav_msgs::msg::Path create_plan(
  nav2_navfn_planner::NavfnPlanner & planner,
  const geometry_msgs::msg::PoseStamped & start, const geometry_msgs::msg::PoseStamped & goal)
{
#if NAVFN_SMT_PLUGIN_API >= 3
  return planner.createPlan(start, goal, {}, [] {return false;});
#elif NAVFN_SMT_PLUGIN_API == 2
  return planner.createPlan(start, goal, [] {return false;});
#else
  return planner.createPlan(start, goal);
#endif
}

static void answer(int outcome, const std::string & message, const nav_msgs::msg::Path & path)
{
  const auto & log = navfn_smt::log_lines();
  write_i32(outcome);
  write_i32(static_cast<int32_t>(path.poses.size()));
  write_i32(static_cast<int32_t>(log.size()));
  write_i32(static_cast<int32_t>(message.size()));
  write_all(message.data(), message.size());
  for (const auto & ps : path.poses) {
    const auto & p = ps.pose;
    double v[6] = {p.position.x, p.position.y, p.orientation.x, p.orientation.y, p.orientation.z,
      p.orientation.w};
    write_all(v, sizeof(v));
  }
  for (const auto & line : log) {
    write_i32(line.first);
    write_i32(static_cast<int32_t>(line.second.size()));
    write_all(line.second.data(), line.second.size());
  }
}

int main()
{
  for (;;) {
    int32_t head[3];
    double geo[4];
    int32_t flags[4];
    if (!read_all(head, sizeof(head)) || head[0] == 0) {return 0;}
    if (!read_all(geo, sizeof(geo)) || !read_all(flags, sizeof(flags))) {return 1;}
    const unsigned int sx = head[0], sy = head[1];
    std::vector<unsigned char> costs(static_cast<size_t>(sx) * sy);
    std::vector<double> cases(static_cast<size_t>(head[2]) * 12);
    if (!read_all(costs.data(), costs.size()) || !read_all(cases.data(), cases.size() * 8)) {return 1;}

    nav2_costmap_2d::Costmap2D costmap(sx, sy, geo[2], geo[0], geo[1]);
    auto costmap_ros = std::make_shared<nav2_costmap_2d::Costmap2DROS>(&costmap);
    auto node = std::make_shared<Node>();
    const std::string name = "GridBased";
    node->overrides[name + ".tolerance"] = rclcpp::ParameterValue(geo[3]);
    node->overrides[name + ".use_astar"] = rclcpp::ParameterValue(flags[0] != 0);
    node->overrides[name + ".allow_unknown"] = rclcpp::ParameterValue(flags[1] != 0);
    node->overrides[name + ".max_cycles_factor"] = rclcpp::ParameterValue(static_cast<int>(flags[2]));
    node->overrides[name + ".use_final_approach_orientation"] = rclcpp::ParameterValue(flags[3] != 0);
    nav2_navfn_planner::NavfnPlanner planner;
    planner.configure(node, name, std::shared_ptr<TfBuffer>(), costmap_ros);
    planner.activate();

    double seconds = 0.0;
    for (int32_t k = 0; k < head[2]; ++k) {
      std::memcpy(costmap.getCharMap(), costs.data(), costs.size());
      navfn_smt::log_lines().clear();
      const double * c = &cases[static_cast<size_t>(k) * 12];
      auto start = pose_of(c), goal = pose_of(c + 6);
      nav_msgs::msg::Path path;
      int outcome = 0;
      std::string message;
      auto t0 = std::chrono::steady_clock::now();
      try {
        path = create_plan(planner, start, goal);
      } catch (const std::exception & e) {
        outcome = outcome_of(e);
        message = e.what();
      }
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      answer(outcome, message, path);
    }
    planner.deactivate();
    planner.cleanup();
    fwrite(&seconds, 8, 1, stdout);
    fflush(stdout);
  }
}
