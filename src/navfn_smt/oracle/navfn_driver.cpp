// navfn-smt: the oracle's driver around Nav2's NavFn class, compiled with navfn.cpp as it is.
//
// One process serves many requests on stdin, answers on stdout (little-endian, native ints):
//   request:  int32 nx, ny, ncases, astar (0/1); nx*ny cost bytes (NavFn's internal costs);
//             ncases x int32 (sx, sy, gx, gy)
//   answer per case: int32 start_reached, cycles, path_len, trace_len; int64 updates;
//             float32 potential[nx*ny]; float32 path[path_len][2]; int32 trace[trace_len]
//   after the request's cases: float64 seconds spent planning them (from copying the map
//             into costarr to calcPath's return, summed; reading and writing the pipes aside)
// A request with nx == 0 ends the process.  Each case is run as the suite's README states:
// the map bytes as costarr, setGoal, setStart, setupNavFn(true), priInc = 2 * COST_NEUTRAL,
// propNavFnAstar / propNavFnDijkstra(max(nx*ny/20, nx+ny)[, atStart = true]), calcPath(4 * nx).
// The unbounded build (NAVFN_SMT_UNBOUNDED, with a navfn.hpp whose PRIORITYBUFSIZE is
// navfn_smt_buffer_size) gives each buffer nx * ny cells, so no push is ever dropped.
// The traced build (NAVFN_SMT_TRACED, its navfn.cpp with the trace hook) reports cycles, updates
// and the trace; the plain build reports -1 and an empty trace.  The build of a patched fix
// (NAVFN_SMT_CALC_NAVFN, a navfn.cpp patched with one of patches/<fix>/: the fix lives in
// calcNavFn*, its cycle limit, its further call) calls calcNavFnAstar / calcNavFnDijkstra(atStart = true),
// which run setupNavFn(true) and the propagation as the patch makes it, before calcPath(4 * nx).
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include "nav2_navfn_planner/navfn.hpp"

using nav2_navfn_planner::NavFn;

static std::vector<int32_t> g_trace;
static int64_t g_updates = 0;
static int32_t g_cycles = 0;
#ifdef NAVFN_SMT_TRACED
static const bool g_traced = true;
#else
static const bool g_traced = false;
#endif

void navfn_smt_cycle(const int * cells, int n)
{
  g_cycles += n > 0 ? 1 : 0;
  g_updates += n;
  g_trace.push_back(n);
  g_trace.insert(g_trace.end(), cells, cells + n);
}

#ifdef NAVFN_SMT_UNBOUNDED
int navfn_smt_buffer_size = 0;  // PRIORITYBUFSIZE of the unbounded build: nx * ny, set per map
#endif

static bool read_all(void * p, size_t n) {return n == 0 || fread(p, 1, n, stdin) == n;}
static void write_all(const void * p, size_t n) {if (n) {fwrite(p, 1, n, stdout);}}

int main()
{
  NavFn * nav = nullptr;
  int cur_nx = -1, cur_ny = -1;
  for (;;) {
    int32_t head[4];
    if (!read_all(head, sizeof(head)) || head[0] <= 0) {
      break;
    }
    const int nx = head[0], ny = head[1], ncases = head[2];
    const bool astar = head[3] != 0;
    std::vector<unsigned char> costs(static_cast<size_t>(nx) * ny);
    std::vector<int32_t> cases(static_cast<size_t>(ncases) * 4);
    if (!read_all(costs.data(), costs.size()) || !read_all(cases.data(), cases.size() * 4)) {
      return 2;
    }
    if (nav == nullptr || nx != cur_nx || ny != cur_ny) {
      delete nav;
#ifdef NAVFN_SMT_UNBOUNDED
      navfn_smt_buffer_size = nx * ny;  // the constructor allocates the buffers
#endif
      nav = new NavFn(nx, ny);
      cur_nx = nx;
      cur_ny = ny;
    }
    double planning = 0.0;
    for (int c = 0; c < ncases; c++) {
      const auto t0 = std::chrono::steady_clock::now();
      int start[2] = {cases[4 * c], cases[4 * c + 1]};
      int goal[2] = {cases[4 * c + 2], cases[4 * c + 3]};
      std::memcpy(nav->costarr, costs.data(), costs.size());
      g_trace.clear();
      g_updates = 0;
      g_cycles = 0;
      nav->setGoal(goal);
      nav->setStart(start);
      bool reached;
#ifdef NAVFN_SMT_CALC_NAVFN
      // a patched fix lives in calcNavFn*: setupNavFn(true), then propagation with the patch's
      // cycle limit (priInc stays the constructor's 2 * COST_NEUTRAL)
#ifdef NAVFN_SMT_CANCEL_CHECKER
      auto never = []() {return false;};
      reached = astar ? nav->calcNavFnAstar(never) : nav->calcNavFnDijkstra(never, true);
#else
      reached = astar ? nav->calcNavFnAstar() : nav->calcNavFnDijkstra(true);
#endif
#else
      nav->setupNavFn(true);
      nav->priInc = 2 * COST_NEUTRAL;
      const int cycles = std::max(nx * ny / 20, nx + ny);
#ifdef NAVFN_SMT_CANCEL_CHECKER
      auto never = []() {return false;};
      reached = astar ? nav->propNavFnAstar(cycles, never) : nav->propNavFnDijkstra(cycles, never, true);
#else
      reached = astar ? nav->propNavFnAstar(cycles) : nav->propNavFnDijkstra(cycles, true);
#endif
#endif
      const int len = nav->calcPath(4 * nx);
      planning += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      int32_t ints[4] = {reached ? 1 : 0, g_traced ? g_cycles : -1, len > 0 ? len : 0,
        static_cast<int32_t>(g_trace.size())};
      int64_t updates = g_traced ? g_updates : -1;
      write_all(ints, sizeof(ints));
      write_all(&updates, sizeof(updates));
      write_all(nav->potarr, static_cast<size_t>(nx) * ny * sizeof(float));
      for (int i = 0; i < (len > 0 ? len : 0); i++) {
        float xy[2] = {nav->pathx[i], nav->pathy[i]};
        write_all(xy, sizeof(xy));
      }
      write_all(g_trace.data(), g_trace.size() * sizeof(int32_t));
    }
    write_all(&planning, sizeof(planning));
    fflush(stdout);
  }
  delete nav;
  return 0;
}
