// GraspIt!'s search energies (see graspkit/planning/search_energy.hpp for the formulas).

#include "graspkit/planning/search_energy.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <memory>

#include "graspkit/collision/contact_search.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/grasp/quality.hpp"
#include "graspkit/model/body_ref.hpp"
#include "graspkit/model/robot.hpp"
#include "graspkit/planning/close_reach.hpp"
#include "graspkit/planning/planning_scene.hpp"
#include "graspkit/planning/search_energy.hpp"
#include "graspkit/planning/search_state.hpp"
#include "planning/sample_bound.hpp"

namespace graspkit {

namespace {

// GraspIt!'s contact energy weighs a contact facing away from the object like 50 mm of distance
// per unit of (1 - cos).
constexpr double kNormalWeight = 50.0;

// Potential quality: a virtual contact counts when its wrench scale exceeds this.
constexpr double kPotentialCountThreshold = 0.25;
constexpr double kPotentialRange = 50.0;     // mm: farther contacts scale to 0
constexpr double kPotentialMinCosine = 0.7;  // contacts facing farther away scale to 0

// Strict autograsp: how far the palm may approach before closing, mm.
constexpr double kStrictApproach = 30.0;
// GraspIt!'s weights of volume and epsilon in the autograsp-quality energy.
constexpr double kVolumeWeight = 30.0;
constexpr double kEpsilonWeight = 100.0;

struct ContactSample {
  Vector3 toObject = Vector3::Zero();  // from the virtual contact to the nearest object point
  double distance = 0.0;
  double cosine = 1.0;  // between the contact normal and toObject
};

// The nearest object point to each virtual contact, remembered between evaluations: the object
// does not move while a search runs, so the distance to the last nearest point bounds the new
// distance, and a bounded query is several times cheaper than an open one.
class NearestPoints {
 public:
  // The nearest object point to a virtual contact. With `within`, a contact whose nearest point
  // lies farther is answered `beyond` at the cost of a query bounded by `within`.
  struct Answer {
    std::optional<Vector3> point;  // none when beyond, or for an object without triangles
    bool beyond = false;
  };

  Answer find(const PlanningScene& scene, const PlacedVirtualContact& contact,
              double within = std::numeric_limits<double>::infinity()) {
    const auto i = static_cast<std::size_t>(contact.index);
    if (last_.size() <= i) last_.resize(i + 1);
    std::optional<SurfacePoint> nearest;
    if (last_[i]) {
      // The object has triangles (one was nearest before), so nothing within `within` means
      // the contact is beyond it.
      const double bound = (*last_[i] - contact.point).norm() * (1.0 + 1e-9) + 1e-9;
      nearest = scene.nearestObjectPoint(contact.point, std::min(bound, within));
      if (!nearest && bound > within) return {std::nullopt, true};
    }
    if (!nearest) nearest = scene.nearestObjectPoint(contact.point);
    if (!nearest) return {};
    last_[i] = nearest->point;
    return {nearest->point, nearest->distance > within};
  }

  // What the object's box and ball say of the contact's sample before any query.
  planning::SampleBound bound(const PlacedVirtualContact& contact) const {
    return planning::sampleBound(object_, contact.point, contact.normal);
  }

  // Forgets the last points when the object moved, and takes its bounds: once per evaluation,
  // before find and bound.
  // The bounds decide, so the object is known by its mesh, held here so that no other mesh can
  // take its address, and its pose.
  void refresh(const PlanningScene& scene) {
    const Transform objectPose = bodyPose(scene.world(), scene.object());
    const auto& mesh = bodyModel(scene.world(), scene.object()).mesh;
    if (mesh == mesh_ && objectPose.isApprox(object_pose_, 0.0)) return;
    mesh_ = mesh;
    object_pose_ = objectPose;
    last_.clear();
    object_ = mesh ? planning::objectBounds(*mesh, objectPose) : planning::ObjectBounds{};
  }

 private:
  std::shared_ptr<const TriangleMesh> mesh_;  // the object's
  Transform object_pose_ = Transform(Eigen::Matrix4d::Zero());
  std::vector<std::optional<Vector3>> last_;
  planning::ObjectBounds object_;
};

// The least a contact's energy term can be, from the bound alone.
double leastTerm(const planning::SampleBound& b) {
  return b.distance + kNormalWeight * (1.0 - b.cosine);
}

// The contact's sample; nullopt when its nearest object point lies beyond `within`.
std::optional<ContactSample> sample(const PlanningScene& scene, const PlacedVirtualContact& contact,
                                    NearestPoints& cache,
                                    double within = std::numeric_limits<double>::infinity()) {
  ContactSample s;
  const NearestPoints::Answer nearest = cache.find(scene, contact, within);
  if (nearest.beyond) return std::nullopt;
  if (!nearest.point) return s;  // an object without triangles: nothing to approach
  s.toObject = *nearest.point - contact.point;
  s.distance = s.toObject.norm();
  s.cosine = s.distance > 0 ? contact.normal.dot(s.toObject) / s.distance : 1.0;
  return s;
}

// The mean over virtual contacts. With a finite `bound`, the sum stops once the terms summed and
// the least the others can be (NearestPoints::bound) exceed it, returning that mean: above the
// bound, as a true sum would be. Every term is >= 0 but for rounding, below 1e-13, which the
// 1e-9 margin covers. A sum that stays below the bound is made of the same terms in the same
// order as a full one.
double contactEnergy(const PlanningScene& scene, NearestPoints& cache,
                     double bound = std::numeric_limits<double>::infinity()) {
  const auto contacts = scene.virtualContacts();
  if (contacts.empty()) return 0.0;
  cache.refresh(scene);
  const auto count = static_cast<double>(contacts.size());
  const double stop = (bound + 1e-9) * count;
  thread_local std::vector<double> least;
  least.assign(contacts.size(), 0.0);
  double rest = 0.0;  // the least the terms not yet summed can add
  if (std::isfinite(stop)) {
    for (std::size_t i = 0; i < contacts.size(); ++i)
      rest += least[i] = leastTerm(cache.bound(contacts[i]));
    if (rest > stop) return rest / count;
  }
  double total = 0.0;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const ContactSample s = *sample(scene, contacts[i], cache);
    total += s.distance + kNormalWeight * (1.0 - s.cosine);
    rest = std::max(0.0, rest - least[i]);
    if (total + rest > stop) return (total + rest) / count;
  }
  return total / count;
}

// GraspIt!'s potentialQualityScalingFunction (3.14 is its constant, not pi).
double potentialScale(double distance, double cosine) {
  if (cosine < kPotentialMinCosine || distance > kPotentialRange) return 0.0;
  return std::cos(3.14 * distance / kPotentialRange) + 1.0;
}

double potentialQualityEnergy(const PlanningScene& scene, NearestPoints& cache) {
  const auto& models = scene.virtualContactModels();
  cache.refresh(scene);
  std::vector<std::vector<Vector6>> wrenches;
  for (const PlacedVirtualContact& contact : scene.virtualContacts()) {
    // A contact beyond the potential's range, or facing too far from the object's ball, scales
    // to 0: no need for its exact nearest point.
    const planning::SampleBound b = cache.bound(contact);
    if (b.distance > kPotentialRange || b.cosine < kPotentialMinCosine) continue;
    const std::optional<ContactSample> s = sample(scene, contact, cache, kPotentialRange);
    if (!s) continue;
    const double scale = potentialScale(s->distance, s->cosine);
    if (scale <= kPotentialCountThreshold) continue;
    const VirtualContact& source = models[static_cast<std::size_t>(contact.index)];
    const Matrix3 frame = contact.frame.linear();
    std::vector<Vector6> set;
    for (const auto& edge : source.frictionEdges) {
      const Vector3 force =
          frame * Vector3(source.sCof * edge[0], source.sCof * edge[1], 1.0) * scale;
      Vector6 w = Vector6::Zero();
      w.head<3>() = force;
      set.push_back(w);
    }
    if (!set.empty()) wrenches.push_back(std::move(set));
  }
  if (wrenches.size() < 3) return 1.0;
  WrenchSpaceOptions options;
  options.dimensions = {true, true, true, false, false, false};
  // The planner's hottest quality: the nearest facet alone, not the whole hull.
  options.method = HullMethod::NearestFacet;
  return -epsilonQuality(graspWrenchSpace(wrenches, options));
}

class ContactEnergy final : public SearchEnergy {
 public:
  double evaluate(PlanningScene& scene) override { return contactEnergy(scene, cache_); }
  double evaluateBelow(PlanningScene& scene, double bound) override {
    return contactEnergy(scene, cache_, bound);
  }
  bool expensive() const override { return false; }

 private:
  NearestPoints cache_;
};

class PotentialQualityEnergy final : public SearchEnergy {
 public:
  double evaluate(PlanningScene& scene) override { return potentialQualityEnergy(scene, cache_); }
  bool expensive() const override { return false; }

 private:
  NearestPoints cache_;
};

class GuidedPotentialQualityEnergy final : public SearchEnergy {
 public:
  double evaluate(PlanningScene& scene) override {
    return evaluateBelow(scene, std::numeric_limits<double>::infinity());
  }
  double evaluateBelow(PlanningScene& scene, double bound) override {
    const double quality = potentialQualityEnergy(scene, cache_);
    return quality <= 0.0 ? quality : contactEnergy(scene, cache_, bound);
  }
  bool expensive() const override { return false; }

 private:
  NearestPoints cache_;
};

// The energy of the grasp the hand closes to. A close that cannot touch the object
// (close_reach.hpp) is not run: its grasp has no contact, whatever else the fingers meet.
double autoGraspQuality(PlanningScene& scene, std::optional<CloseReach>& reach) {
  if (!reach || reach->model != scene.hand().modelPtr())
    reach = closeReachOf(scene.hand().modelPtr());
  std::vector<Contact> contacts;
  if (closeMayTouchObject(scene, *reach, ContactRequest{}.threshold)) {
    const AutoGraspResult closed = autoGrasp(scene.world(), scene.robot());
    contacts = contactsWith(closed.contacts, scene.object());
  }
  const Grasp grasp =
      analyzeGrasp(scene.world(), scene.robot(), scene.object(), std::move(contacts));
  return -(kVolumeWeight * grasp.volume + kEpsilonWeight * std::max(grasp.epsilon, 0.0));
}

class AutoGraspQualityEnergy final : public SearchEnergy {
 public:
  double evaluate(PlanningScene& scene) override { return autoGraspQuality(scene, reach_); }

 private:
  std::optional<CloseReach> reach_;
};

class StrictAutoGraspEnergy final : public SearchEnergy {
 public:
  double evaluate(PlanningScene& scene) override {
    const Transform start = scene.hand().pose();
    ApproachOptions approach;
    approach.maxDistance = kStrictApproach;
    const AutoGraspResult moved = approachToContact(scene.world(), scene.robot(), approach);
    const bool palmTouches =
        moved.end == MotionEnd::Contact &&
        std::any_of(moved.contacts.begin(), moved.contacts.end(),
                    [&](const Contact& c) { return c.body1 == BodyRef::robotBase(scene.robot()); });
    if (!palmTouches) scene.world().setRobotPose(scene.robot(), start);
    const double quality = autoGraspQuality(scene, reach_);
    return quality == 0.0 ? kUnevaluatedEnergy : quality;
  }

 private:
  std::optional<CloseReach> reach_;
};

template <typename E>
SearchEnergyFactory factory() {
  return [] { return std::make_unique<E>(); };
}

}  // namespace

std::string canonicalEnergyName(std::string_view name) {
  static const std::map<std::string, std::string, std::less<>> graspitNames = {
      {"CONTACT_ENERGY", "contact"},
      {"POTENTIAL_QUALITY_ENERGY", "potential-quality"},
      {"GUIDED_POTENTIAL_QUALITY_ENERGY", "guided-potential-quality"},
      {"AUTO_GRASP_QUALITY_ENERGY", "autograsp-quality"},
      {"STRICT_AUTO_GRASP_ENERGY", "strict-autograsp"},
  };
  auto it = graspitNames.find(name);
  return it == graspitNames.end() ? std::string(name) : it->second;
}

std::string_view energyEpsilonMethod(std::string_view name) {
  const std::string canonical = canonicalEnergyName(name);
  if (canonical == "potential-quality" || canonical == "guided-potential-quality")
    return epsilonMethodName(HullMethod::NearestFacet);
  if (canonical == "autograsp-quality" || canonical == "strict-autograsp")
    return epsilonMethodName(GraspRequest{}.wrenchSpace.method);
  return {};
}

std::vector<std::pair<std::string, SearchEnergyFactory>> builtinSearchEnergies() {
  return {{"contact", factory<ContactEnergy>()},
          {"potential-quality", factory<PotentialQualityEnergy>()},
          {"guided-potential-quality", factory<GuidedPotentialQualityEnergy>()},
          {"autograsp-quality", factory<AutoGraspQualityEnergy>()},
          {"strict-autograsp", factory<StrictAutoGraspEnergy>()}};
}

}  // namespace graspkit
