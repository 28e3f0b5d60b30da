// navfn-smt: the part of Costmap2DROS the planner plugin uses: the master Costmap2D (Nav2's
// own costmap_2d.cpp, compiled with the plugin) and the global frame's name.
#ifndef NAVFN_SMT_PLUGIN_STUB_COSTMAP_2D_ROS_HPP_
#define NAVFN_SMT_PLUGIN_STUB_COSTMAP_2D_ROS_HPP_
#include <string>
#include "nav2_costmap_2d/costmap_2d.hpp"
namespace nav2_costmap_2d
{
class Costmap2DROS
{
public:
  explicit Costmap2DROS(Costmap2D * costmap) : costmap_(costmap) {}
  Costmap2D * getCostmap() {return costmap_;}
  std::string getGlobalFrameID() {return "map";}
  std::string getBaseFrameID() {return "base_link";}

private:
  Costmap2D * costmap_;
};
}  // namespace nav2_costmap_2d
#endif
