#pragma once
// GraspIt!'s simulated-annealing schedules (Ingber's very fast simulated re-annealing): the
// temperature T(k) = T0 exp(-c k^(1/d)), one schedule (YC, YDIMS) for the size of neighbour
// steps and one (HC, HDIMS) for accepting a worse state, and its five presets as data.

#include <array>
#include <cmath>
#include <limits>
#include <string_view>

namespace graspkit::simann {

struct AnnealingParameters {
  std::string_view name;
  double neighbourCooling;  // YC
  double acceptCooling;     // HC
  int neighbourDims;        // YDIMS
  int acceptDims;           // HDIMS
  double neighbourScale;    // NBR_ADJ: multiplies the neighbour temperature
  double energyScale;       // ERR_ADJ: multiplies energies before the Metropolis test
  double startTemperature;  // T0
  long startStep;           // K0: the step the schedule starts at
};

// The presets of GraspIt!'s SimAnn::setParameters.
inline constexpr std::array<AnnealingParameters, 5> kPresets = {{
    {"DEFAULT", 7.0, 7.0, 8, 8, 1.0, 1.0e-6, 1.0e6, 30000},
    {"LOOP", 7.0, 7.0, 8, 8, 1.0, 1.0e-6, 1.0e6, 35000},
    {"MODIFIED", 2.38, 2.38, 8, 8, 1.0e-3, 1.0e-1, 1.0e3, 0},
    {"STRICT", 0.72, 0.22, 2, 2, 1.0, 1.0, 10.0, 0},
    {"ONLINE", 0.24, 0.54, 2, 3, 1.0, 1.0e-2, 10.0, 100},
}};

// Ingber's schedule.
inline double temperature(double t0, double c, long step, int dims) {
  return t0 * std::exp(-c * std::pow(static_cast<double>(step), 1.0 / dims));
}

// Ingber's neighbour distribution: a step in [-1, 1] (times the variable's largest jump) from a
// uniform draw u in [0, 1]; small steps grow more likely as T falls.
inline double neighbourStep(double t, double u) {
  const double v = std::abs(2.0 * u - 1.0);
  const double y = t * (std::pow(1.0 + 1.0 / t, v) - 1.0);
  return u < 0.5 ? -y : y;
}

// The Metropolis probability of moving from energy `from` to `to` at temperature t.
inline double acceptance(double from, double to, double t) {
  return to < from ? 1.0 : std::exp((from - to) / t);
}

// The (scaled) energy above which acceptance(from, to, t) <= u for sure: the exponent is kept
// 1e-9 below log(u), far beyond what rounding in exp can cross. Infinity where no such energy
// is certain (u = 0, a temperature of 0).
inline double rejectionBound(double from, double t, double u) {
  if (!(u > 0.0) || !(t > 0.0)) return std::numeric_limits<double>::infinity();
  return from - t * (std::log(u) - 1e-9);
}

}  // namespace graspkit::simann
