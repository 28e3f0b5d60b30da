// navfn-smt: the part of Costmap2DROS the planner plugin uses: the master Costmap2D (Nav2's
// own costmap_2d.cpp, compiled with the plugin) and the global frame's name; the layers only
// name it.
#ifndef NAVFN_SMT_PLUGIN_STUB_COSTMAP_2D_ROS_HPP_
#define NAVFN_SMT_PLUGIN_STUB_COSTMAP_2D_ROS_HPP_
#include <string>
#include "nav2_costmap_2d/costmap_2d.hpp"
namespace nav2_costmap_2d
{
class LayeredCostmap;

class Costmap2DROS
{
public:
  explicit Costmap2DROS(Costmap2D * costmap) : costmap_(costmap) {}
  Costmap2D * getCostmap() {return costmap_;}
  LayeredCostmap * getLayeredCostmap() {return nullptr;}  // the oracle's layers never ask
  std::string getGlobalFrameID() {return "map";}
  std::string getBaseFrameID() {return "base_link";}

private:
  Costmap2D * costmap_;
};
}  // namespace nav2_costmap_2d
#endif
