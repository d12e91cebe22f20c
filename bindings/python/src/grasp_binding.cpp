// graspkit.Grasp and graspkit.Contacts: a hand's contacts with one object as NumPy arrays, and
// what they can do to it (the wrench space and its quality measures).

#include <fmt/format.h>

#include "graspkit/grasp/grasp.hpp"
#include "graspkit/grasp/quality.hpp"
#include "graspkit/host/subject.hpp"
#include "graspkit/plugin/registry.hpp"
#include "python_support.hpp"

namespace graspkit::python {
namespace {

struct BoundGrasp {
  WorldPtr world;
  Grasp grasp;
};

// The contacts of one grasp, column by column.
struct Contacts {
  WorldPtr world;
  std::vector<Contact> contacts;
};

py::array_t<double> column(const std::vector<Contact>& contacts, Vector3 (*pick)(const Contact&)) {
  py::array_t<double> out({static_cast<py::ssize_t>(contacts.size()), py::ssize_t{3}});
  auto a = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Vector3 v = pick(contacts[i]);
    for (int k = 0; k < 3; ++k) a(static_cast<py::ssize_t>(i), k) = v[k];
  }
  return out;
}

py::array_t<double> scalars(const std::vector<Contact>& contacts, double (*pick)(const Contact&)) {
  py::array_t<double> out(static_cast<py::ssize_t>(contacts.size()));
  for (std::size_t i = 0; i < contacts.size(); ++i)
    out.mutable_at(static_cast<py::ssize_t>(i)) = pick(contacts[i]);
  return out;
}

std::vector<std::string> names(const Contacts& c, bool first) {
  std::vector<std::string> out;
  for (const Contact& contact : c.contacts)
    out.push_back(bodyName(c.world->world, first ? contact.body1 : contact.body2));
  return out;
}

void bindContacts(py::module_& m) {
  py::class_<Contacts>(m, "Contacts",
                       "Contacts, one row each: the hand's link is the first body, the object the "
                       "second. World frame, mm.")
      .def("__len__", [](const Contacts& c) { return c.contacts.size(); })
      .def_property_readonly(
          "points",
          [](const Contacts& c) {
            return column(c.contacts, [](const Contact& x) { return x.position1; });
          },
          "(N, 3): each contact's point on the link.")
      .def_property_readonly(
          "object_points",
          [](const Contacts& c) {
            return column(c.contacts, [](const Contact& x) { return x.position2; });
          },
          "(N, 3): its mate on the object.")
      .def_property_readonly(
          "normals",
          [](const Contacts& c) {
            return column(c.contacts, [](const Contact& x) { return x.normal; });
          },
          "(N, 3) unit normals into the link: the way the object can push it.")
      .def_property_readonly(
          "frames",
          [](const Contacts& c) {
            py::array_t<double> out(
                {static_cast<py::ssize_t>(c.contacts.size()), py::ssize_t{3}, py::ssize_t{3}});
            auto a = out.mutable_unchecked<3>();
            for (std::size_t i = 0; i < c.contacts.size(); ++i)
              for (int r = 0; r < 3; ++r)
                for (int k = 0; k < 3; ++k)
                  a(static_cast<py::ssize_t>(i), r, k) = c.contacts[i].frame(r, k);
            return out;
          },
          "(N, 3, 3): contact frames, columns x, y, z with z the normal.")
      .def_property_readonly(
          "distances",
          [](const Contacts& c) {
            return scalars(c.contacts, [](const Contact& x) { return x.distance; });
          },
          "(N,): separation of the two points, mm.")
      .def_property_readonly(
          "mu",
          [](const Contacts& c) {
            return scalars(c.contacts, [](const Contact& x) { return x.mu; });
          },
          "(N,): friction coefficients from the two materials.")
      .def_property_readonly(
          "torsion",
          [](const Contacts& c) {
            return scalars(c.contacts, [](const Contact& x) { return x.torsion; });
          },
          "(N,): soft fingers' e_tau (mm); 0 for other contacts.")
      .def_property_readonly(
          "models",
          [](const Contacts& c) {
            std::vector<std::string> out;
            for (const Contact& x : c.contacts) out.emplace_back(nameOf(x.model));
            return out;
          },
          "\"point\", \"soft_finger\" or \"frictionless\" per contact.")
      .def_property_readonly(
          "links", [](const Contacts& c) { return names(c, true); }, "The link of each contact.")
      .def_property_readonly(
          "bodies", [](const Contacts& c) { return names(c, false); },
          "The body each link touches.");
}

void bindGraspClass(py::module_& m) {
  py::class_<BoundGrasp>(m, "Grasp", "A hand's contacts with one object and their wrench space.")
      .def_property_readonly(
          "epsilon", [](const BoundGrasp& g) { return g.grasp.epsilon; },
          "GraspIt!'s epsilon quality; -1 without force closure.")
      .def_property_readonly(
          "volume", [](const BoundGrasp& g) { return g.grasp.volume; },
          "The wrench space's volume; 0 when the hull fails.")
      .def_property_readonly("force_closure",
                             [](const BoundGrasp& g) { return g.grasp.forceClosure; })
      .def_property_readonly("contacts",
                             [](const BoundGrasp& g) {
                               return Contacts{g.world, g.grasp.contacts};
                             })
      .def_property_readonly("contact_count",
                             [](const BoundGrasp& g) { return g.grasp.contacts.size(); })
      .def_property_readonly(
          "failure",
          [](const BoundGrasp& g) -> py::object {
            if (g.grasp.wrenchSpace.built) return py::none();
            return py::str(g.grasp.wrenchSpace.failure);
          },
          "Why no wrench space was built (no contacts, too few, qhull's reason); None when it "
          "was.")
      .def(
          "quality",
          [](const BoundGrasp& g, const std::string& name) {
            return Registry::global().makeQualityMeasure(name)->evaluate(g.grasp.wrenchSpace);
          },
          py::arg("name"),
          "A registered quality measure by name (\"epsilon\", \"volume\", a plugin's).")
      .def("__repr__", [](const BoundGrasp& g) {
        return fmt::format("<graspkit.Grasp: {} contacts, epsilon {:.6g}, volume {:.6g}>",
                           g.grasp.contacts.size(), g.grasp.epsilon, g.grasp.volume);
      });
}

BodyRef firstGraspable(const WorldHandle& world) {
  try {
    return host::defaultObject(world.world);
  } catch (const Error& e) {
    throw py::value_error(e.what());
  }
}

}  // namespace

void bindGrasp(py::module_& m) {
  bindContacts(m);
  bindGraspClass(m);
  // robot.grasp() is defined here, beside the Grasp it makes (Robot is bound before).
  py::class_<RobotView> robot = py::reinterpret_borrow<py::class_<RobotView>>(m.attr("Robot"));
  robot.def(
      "grasp",
      [](const RobotView& r, const py::object& object, const std::string& gws) {
        GraspRequest request;
        try {
          request.wrenchSpace.type = parseNamed<WrenchSpaceType>(gws, "wrench space");
        } catch (const Error& e) {
          throw py::value_error(e.what());
        }
        const BodyRef target =
            object.is_none() ? firstGraspable(*r.world) : toBodyRef(*r.world, object, "object");
        r.robot();
        return BoundGrasp{r.world, analyzeGrasp(r.world->world, r.index, target, request)};
      },
      py::arg("object") = py::none(), py::kw_only(),
      py::arg("gws") = std::string(nameOf(GraspRequest{}.wrenchSpace.type)),
      "The hand's contacts with `object` (a Body or a name; default: the first graspable body) "
      "as the world stands, their wrench space (L1 or Linf) and its quality.");
}

}  // namespace graspkit::python
