// The observation of vb's learned baselines RL, MCL and ACL (docs/learning.md): 76 float32
// features from one Observation, the same operations in the same order as the Python definition
// the policies were trained with (python/vb_gym/learned.py; a test checks both agree).
//
//  - 12 state features, scaled and clipped to [-kLearnedClip, kLearnedClip]: heading error to
//    the local goal / pi, local goal forward and left (vehicle frame) / 10 m, goal distance /
//    100 m, forward speed / max speed (4 m/s), roll and pitch / 0.5 rad, roll, pitch and yaw rates (rad/s),
//    vertical speed / 2 m/s, the steering applied in the last physics step.
//  - 64 elevation features: the egocentric elevation crop of 16 x 16 cells of 1 m relative to the
//    chassis height (unknown cells 0), mean of each 2 x 2 block (8 x 8, row-major) / 2 m, clipped.
#pragma once

#include "vb/controllers/observation.h"

namespace vb::controllers {

constexpr int kLearnedStateFeatures = 12;
constexpr int kLearnedCropCells = 16;
constexpr double kLearnedCropResolution_m = 1.0;
constexpr int kLearnedPool = 2;
constexpr int kLearnedFeatures =
    kLearnedStateFeatures + (kLearnedCropCells / kLearnedPool) * (kLearnedCropCells / kLearnedPool);
constexpr float kLearnedClip = 3.0f;
constexpr double kLearnedMaxSpeed_mps = 4.0;
constexpr double kLearnedDecisionPeriod_s = 0.1;

// The observation the features need: the local goal (10 m look-ahead, replanned every 0.1 s)
// and the one elevation crop.
ObservationConfig LearnedObservationConfig();

// Writes kLearnedFeatures values to out. `applied_steering` is the steering command of the last
// physics step (clamped to [-1, 1]; 0 at the start), which the gym reports in its state.
// obs.crops[0] must be the crop of LearnedObservationConfig(). `max_speed_mps` scales the speed
// feature: the episode's target speed, as the original scales its RL observation and action by
// its CLI speed (the policies were trained at kLearnedMaxSpeed_mps). No allocation.
void LearnedFeatures(const Observation& obs, double applied_steering, float* out,
                     double max_speed_mps = kLearnedMaxSpeed_mps);

}  // namespace vb::controllers
