#include "annealing_chain.hpp"

#include <algorithm>
#include <limits>

namespace graspkit::simann {

namespace {
constexpr int kNeighbourTries = 11;  // GraspIt!: attempts 0..10
constexpr int kRedrawLimit = 100;    // GraspIt!'s guard on redrawing an out-of-range value
constexpr double kRangeTolerance = 1e-7;
}  // namespace

std::uint64_t chainSeed(std::uint64_t seed, int index) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(index + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

AnnealingChain::AnnealingChain(std::shared_ptr<PlanningScene> scene,
                               std::unique_ptr<SearchEnergy> energy, const ChainSettings& settings,
                               std::uint64_t seed, SearchState start)
    : scene_(std::move(scene)),
      energy_(std::move(energy)),
      settings_(settings),
      random_(seed),
      current_(std::move(start)),
      best_(settings.bestListSize, settings.distanceThreshold,
            [space = scene_->spacePtr(), radius = scene_->objectRadius()](
                std::span<const double> a, std::span<const double> b) {
              return space->distance(a, b, radius);
            }),
      schedule_step_(settings.parameters.startStep) {}

double AnnealingChain::uniform() {
  return static_cast<double>(random_() >> 11) * 0x1.0p-53;
}

std::vector<double> AnnealingChain::neighbour(double t) {
  std::vector<double> values = current_.values;
  const auto variables = scene_->space().variables();
  for (std::size_t i = 0; i < values.size(); ++i) {
    const SearchVariable& variable = variables[i];
    if (variable.fixed) continue;
    const double jump = variable.jump * settings_.jumpScale;
    double v = values[i];
    for (int loop = 0; loop < kRedrawLimit; ++loop) {
      v = values[i] + neighbourStep(t, uniform()) * jump;
      if (variable.circular) {
        if (v > variable.max)
          v -= variable.range();
        else if (v < variable.min)
          v += variable.range();
      }
      if (v > variable.max && v - variable.max < kRangeTolerance) v = variable.max;
      if (v < variable.min && variable.min - v < kRangeTolerance) v = variable.min;
      if (v >= variable.min && v <= variable.max) break;
    }
    // GraspIt! keeps an out-of-range value after 100 draws; it is clamped here instead.
    values[i] = std::clamp(v, variable.min, variable.max);
  }
  return values;
}

bool AnnealingChain::step() {
  const AnnealingParameters& p = settings_.parameters;
  const double tNeighbour =
      temperature(p.startTemperature, p.neighbourCooling, schedule_step_, p.neighbourDims) *
      p.neighbourScale;
  const double tAccept =
      temperature(p.startTemperature, p.acceptCooling, schedule_step_, p.acceptDims);
  ++steps_;
  const bool lazy =
      settings_.checkCollisionsLast && !energy_->expensive() && energy_->rejectsCollisions();
  const bool advanced =
      lazy ? stepCheckingLast(tNeighbour, tAccept) : stepCheckingFirst(tNeighbour, tAccept);
  if (advanced) schedule_step_ += settings_.scheduleStride;
  return advanced;
}

// GraspIt!'s order: up to 11 neighbours until a legal one, then the Metropolis test.
bool AnnealingChain::stepCheckingFirst(double tNeighbour, double tAccept) {
  const double scale = settings_.parameters.energyScale;
  for (int attempt = 0; attempt < kNeighbourTries; ++attempt) {
    std::vector<double> candidate = neighbour(tNeighbour);
    const std::optional<double> energy = evaluateState(*scene_, *energy_, candidate);
    if (!energy) continue;
    if (acceptance(scale * current_.energy, scale * *energy, tAccept) > uniform())
      moveTo(std::move(candidate), *energy);
    return true;
  }
  return false;
}

// Evaluate first; only a neighbour the Metropolis test accepts is checked for collisions, and a
// colliding one is replaced by a new neighbour, as GraspIt! replaces an illegal one. The test's
// random number is drawn before evaluating (nothing else draws in between, so the stream is
// the same), which tells the energy where it may stop: past the bound it is rejected anyway.
bool AnnealingChain::stepCheckingLast(double tNeighbour, double tAccept) {
  const double scale = settings_.parameters.energyScale;
  for (int attempt = 0; attempt < kNeighbourTries; ++attempt) {
    std::vector<double> candidate = neighbour(tNeighbour);
    scene_->place(candidate);
    const double u = uniform();
    const double bound = scale > 0.0 ? rejectionBound(scale * current_.energy, tAccept, u) / scale
                                     : std::numeric_limits<double>::infinity();
    const double energy = energy_->evaluateBelow(*scene_, bound);
    if (!(acceptance(scale * current_.energy, scale * energy, tAccept) > u)) return true;
    if (scene_->handCollides()) continue;
    moveTo(std::move(candidate), energy);
    return true;
  }
  return false;
}

void AnnealingChain::moveTo(std::vector<double> values, double energy) {
  current_ = SearchState{std::move(values), energy};
  best_.offer(current_);
}

void AnnealingChain::runTo(std::int64_t target) {
  while (steps_ < target) step();
}

bool AnnealingChain::runTo(std::int64_t target, const std::function<bool()>& keepGoing) {
  while (steps_ < target) {
    if (!keepGoing()) return false;
    step();
  }
  return true;
}

}  // namespace graspkit::simann
