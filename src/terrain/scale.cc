#include "vb/terrain/scale.h"

#include <cmath>
#include <cstdlib>
#include <string>

#include "vb/engine/error.h"

namespace vb::terrain {

TaskSpec ScaleTask(const TaskSpec& task, double factor) {
  VB_DEMAND(factor > 0.0 && std::isfinite(factor));
  TaskSpec out = task;
  out.scale = task.scale * factor;
  out.size_x_m = task.size_x_m * factor;
  out.size_y_m = task.size_y_m * factor;
  out.min_height_m = task.min_height_m * factor;
  out.max_height_m = task.max_height_m * factor;
  for (double& h : out.heights.heights_m) h *= factor;
  for (RockSpec& rock : out.rocks) {
    rock.x_m *= factor;
    rock.y_m *= factor;
  }
  for (TreeSpec& tree : out.trees) {
    tree.x_m *= factor;
    tree.y_m *= factor;
  }
  for (StartGoalPair& pair : out.pairs) {
    pair.start_m *= factor;
    pair.goal_m *= factor;
    for (Vec2& p : pair.path_m) p *= factor;
  }
  return out;
}

std::optional<double> ParseScaleFactor(std::string_view text) {
  const std::string s(text);
  if (s.empty()) return std::nullopt;
  auto parse = [](const std::string& part, double* value) {
    if (part.empty()) return false;
    char* end = nullptr;
    *value = std::strtod(part.c_str(), &end);
    return *end == '\0' && std::isfinite(*value);
  };
  double value = 0.0;
  const size_t slash = s.find('/');
  if (slash == std::string::npos) {
    if (!parse(s, &value)) return std::nullopt;
  } else {
    double num = 0.0;
    double den = 0.0;
    if (!parse(s.substr(0, slash), &num) || !parse(s.substr(slash + 1), &den) || den == 0.0) {
      return std::nullopt;
    }
    value = num / den;
  }
  if (!(value > 0.0) || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace vb::terrain
