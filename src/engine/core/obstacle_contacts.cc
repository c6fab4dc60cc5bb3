// The order PhysicsWorld::ObstacleContacts() promises, shared by both adapters.
#include <algorithm>

#include "vb/engine/physics_world.h"

namespace vb::engine {

void SortObstacleContacts(std::vector<ObstacleContact>* contacts) {
  std::sort(contacts->begin(), contacts->end(),
            [](const ObstacleContact& x, const ObstacleContact& y) {
              return x.body != y.body ? x.body < y.body : x.obstacle_tag < y.obstacle_tag;
            });
  contacts->erase(std::unique(contacts->begin(), contacts->end(),
                              [](const ObstacleContact& x, const ObstacleContact& y) {
                                return x.body == y.body && x.obstacle_tag == y.obstacle_tag;
                              }),
                  contacts->end());
}

}  // namespace vb::engine
