// navfn-smt: the oracle's driver around Nav2's global costmap layers, compiled with
// costmap_2d.cpp, layer.cpp, layered_costmap.cpp, costmap_layer.cpp, footprint.cpp,
// costmap_math.cpp and the layer plugins (static_layer.cpp, inflation_layer.cpp, and
// legacy_inflation_layer.cpp where the version has it) as they are.
//
// One process serves many requests on stdin, answers on stdout (little-endian, native ints):
//   request:  int32 width, height, nlayers; float32 resolution; float64 origin_x, origin_y;
//             int64 track_unknown_space, use_maximum, lethal_cost_threshold, unknown_cost_value,
//             trinary_costmap, inscribed_obstacle_cost_value (the int64 of a ROS integer parameter);
//             float64 robot_radius;
//             float32 footprint_padding;
//             per layer: int32 kind (0 StaticLayer, 1 InflationLayer, 2 LegacyInflationLayer),
//             enabled, inflate_unknown, inflate_around_unknown; float64 inflation_radius,
//             cost_scaling_factor, custom_inscribed_radius;
//             int8 occupancy[width * height] (nav_msgs/OccupancyGrid's data, row 0 at the origin)
//   answer:   int32 size_x, size_y, status (0 ok, 1 a layer kind this version lacks);
//             uint8 master[size_x * size_y]; float64 inscribed_radius, circumscribed_radius
// A request with width == 0 ends the process.
//
// Each request does what Costmap2DROS does on configure and on its first update, with nothing
// of its arithmetic in this file: a LayeredCostmap (not rolling; the global frame is the map's
// frame), each layer initialized on a node holding the request's parameters and added in
// order, the footprint made from the robot radius (makeFootprintFromRadius) and padded
// (padFootprint), set on the LayeredCostmap; the map delivered to the static layer's own
// subscription as map_server would publish it; then updateMap at the origin.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "nav2_costmap_2d/footprint.hpp"
#include "nav2_costmap_2d/inflation_layer.hpp"
#include "nav2_costmap_2d/layered_costmap.hpp"
#include "nav2_costmap_2d/static_layer.hpp"
#ifdef NAVFN_SMT_LEGACY_LAYER
#include "nav2_costmap_2d/legacy_inflation_layer.hpp"
#endif

#include "navfn_smt/node_types.hpp"

static bool read_all(void * p, size_t n) {return n == 0 || fread(p, 1, n, stdin) == n;}
static void write_all(const void * p, size_t n) {if (n) {fwrite(p, 1, n, stdout);}}

struct LayerRequest
{
  int32_t kind, enabled, inflate_unknown, inflate_around_unknown;
  double inflation_radius, cost_scaling_factor, custom_inscribed_radius;
};

static std::shared_ptr<nav2_costmap_2d::Layer> make_layer(int kind)
{
  if (kind == 0) {return std::make_shared<nav2_costmap_2d::StaticLayer>();}
  if (kind == 1) {return std::make_shared<nav2_costmap_2d::InflationLayer>();}
#ifdef NAVFN_SMT_LEGACY_LAYER
  if (kind == 2) {return std::make_shared<nav2_costmap_2d::LegacyInflationLayer>();}
#endif
  return nullptr;
}

static void set(Node & node, const std::string & name, const rclcpp::ParameterValue & v) {node.overrides[name] = v;}

int main()
{
  for (;;) {
    int32_t head[3];
    float resolution, padding;
    double origin[2], radius;
    int64_t p[6];
    if (!read_all(head, sizeof(head)) || head[0] == 0) {return 0;}
    if (!read_all(&resolution, 4) || !read_all(origin, 16) || !read_all(p, sizeof(p)) || !read_all(&radius, 8) ||
      !read_all(&padding, 4)) {return 1;}
    std::vector<LayerRequest> layers(head[2]);
    for (auto & l : layers) {
      if (!read_all(&l.kind, 16) || !read_all(&l.inflation_radius, 24)) {return 1;}
    }
    auto grid = std::make_shared<nav_msgs::msg::OccupancyGrid>();
    grid->header.frame_id = "map";
    grid->info.width = head[0];
    grid->info.height = head[1];
    grid->info.resolution = resolution;
    grid->info.origin.position.x = origin[0];
    grid->info.origin.position.y = origin[1];
    grid->data.resize(static_cast<size_t>(head[0]) * head[1]);
    if (!read_all(grid->data.data(), grid->data.size())) {return 1;}

    // Costmap2DROS's own parameters, as it declares them for its layers to read
    auto node = std::make_shared<Node>();
    node->declare_parameter("track_unknown_space", rclcpp::ParameterValue(p[0] != 0));
    node->declare_parameter("use_maximum", rclcpp::ParameterValue(p[1] != 0));
    node->declare_parameter("lethal_cost_threshold", rclcpp::ParameterValue(p[2]));
    node->declare_parameter("unknown_cost_value", rclcpp::ParameterValue(p[3]));
    node->declare_parameter("trinary_costmap", rclcpp::ParameterValue(p[4] != 0));
    node->declare_parameter("inscribed_obstacle_cost_value", rclcpp::ParameterValue(p[5]));
    node->declare_parameter("transform_tolerance", rclcpp::ParameterValue(0.3));
    node->declare_parameter("map_topic", rclcpp::ParameterValue(std::string("map")));

    nav2_costmap_2d::LayeredCostmap layered("map", false, p[0] != 0);
    // as Costmap2DROS::on_configure: the costmap has its size and resolution before its layers
    // load (an inflation layer that computes its caches at zero resolution gets an infinite cell
    // radius: (unsigned) of infinity is 0 on x86-64 but UINT_MAX on arm64, a 4 GB cost table)
    layered.resizeMap(head[0], head[1], resolution, origin[0], origin[1]);
    TfBuffer tf;
    int32_t status = 0;
    for (size_t i = 0; i < layers.size(); ++i) {
      const auto & l = layers[i];
      const std::string name = "layer" + std::to_string(i);
      set(*node, name + ".enabled", rclcpp::ParameterValue(l.enabled != 0));
      set(*node, name + ".inflation_radius", rclcpp::ParameterValue(l.inflation_radius));
      set(*node, name + ".cost_scaling_factor", rclcpp::ParameterValue(l.cost_scaling_factor));
      set(*node, name + ".inflate_unknown", rclcpp::ParameterValue(l.inflate_unknown != 0));
      set(*node, name + ".inflate_around_unknown", rclcpp::ParameterValue(l.inflate_around_unknown != 0));
      set(*node, name + ".custom_inscribed_radius", rclcpp::ParameterValue(l.custom_inscribed_radius));
      set(*node, name + ".map_topic", rclcpp::ParameterValue(std::string("map")));
      auto layer = make_layer(l.kind);
      if (!layer) {
        status = 1;
        break;
      }
      layer->initialize(&layered, name, &tf, node, nullptr);
      layered.addPlugin(layer);
    }
    std::vector<geometry_msgs::msg::Point> footprint = nav2_costmap_2d::makeFootprintFromRadius(radius);
    nav2_costmap_2d::padFootprint(footprint, padding);
    if (status == 0) {
      layered.setFootprint(footprint);
      node->deliver(*grid);
      layered.updateMap(0.0, 0.0, 0.0);
    }
    auto * master = layered.getCostmap();
    int32_t out[3] = {static_cast<int32_t>(master->getSizeInCellsX()),
      static_cast<int32_t>(master->getSizeInCellsY()), status};
    if (status != 0) {out[0] = out[1] = 0;}
    write_all(out, sizeof(out));
    write_all(master->getCharMap(), static_cast<size_t>(out[0]) * out[1]);
    double radii[2] = {layered.getInscribedRadius(), layered.getCircumscribedRadius()};
    write_all(radii, sizeof(radii));
    fflush(stdout);
  }
}
