// navfn-smt: the part of Costmap2DROS the planner plugin uses: the master Costmap2D (Nav2's
// own costmap_2d.cpp, compiled with the plugin) and the global frame's name; the layers only
// name it.
#ifndef NAVFN_SMT_PLUGIN_STUB_COSTMAP_2D_ROS_HPP_
#define NAVFN_SMT_PLUGIN_STUB_COSTMAP_2D_ROS_HPP_
#include <memory>
#include <string>
#include "nav2_costmap_2d/costmap_2d.hpp"
namespace nav2_costmap_2d
{
class LayeredCostmap;

class Costmap2DROS
{
public:
  explicit Costmap2DROS(Costmap2D * costmap) : costmap_(costmap) {}
  // by name, as Nav2's tests make one: configured, its master costmap is Costmap2DROS's
  // default, 5 m x 5 m at 0.1 m (50 x 50 cells) at the origin, free
  explicit Costmap2DROS(const std::string &) : own_(std::make_unique<Costmap2D>()), costmap_(own_.get()) {}
  template<typename StateT>
  void on_configure(const StateT &) {costmap_->resizeMap(50, 50, 0.1, 0.0, 0.0);}
  Costmap2D * getCostmap() {return costmap_;}
  LayeredCostmap * getLayeredCostmap() {return nullptr;}  // the oracle's layers never ask
  std::string getGlobalFrameID() {return "map";}
  std::string getBaseFrameID() {return "base_link";}

private:
  std::unique_ptr<Costmap2D> own_;
  Costmap2D * costmap_;
};
}  // namespace nav2_costmap_2d
#endif
