// graspkit.Dataset, load_dataset, plan_dataset and generate_object: grasp datasets as `graspkit
// batch` writes them (docs/dataset.md), one object's planned from Python, and the procedural
// objects `graspkit objects` generates.

#include <cmath>

#include <fmt/format.h>

#include "graspkit/host/dataset_task.hpp"
#include "graspkit/host/object_task.hpp"
#include "graspkit/io/dataset/grasp_dataset_file.hpp"
#include "graspkit/model/material.hpp"
#include "python_support.hpp"

namespace graspkit::python {
namespace {

py::array_t<double> points(const std::vector<Vector3>& list) {
  py::array_t<double> out({static_cast<py::ssize_t>(list.size()), py::ssize_t{3}});
  auto a = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < list.size(); ++i)
    for (int k = 0; k < 3; ++k) a(static_cast<py::ssize_t>(i), k) = list[i][k];
  return out;
}

void bindDatasetGrasp(py::module_& m) {
  py::class_<DatasetGrasp>(m, "DatasetGrasp",
                           "One grasp of a dataset, in the object's frame (the object at the "
                           "origin).")
      .def_property_readonly(
          "pose", [](const DatasetGrasp& g) { return toMatrix(g.grasp); },
          "The closed hand's pose, 4x4, mm.")
      .def_property_readonly("pregrasp", [](const DatasetGrasp& g) { return toMatrix(g.pregrasp); })
      .def_property_readonly("open_dofs", [](const DatasetGrasp& g) { return toArray(g.openDofs); })
      .def_property_readonly("closed_dofs",
                             [](const DatasetGrasp& g) { return toArray(g.closedDofs); })
      .def_readonly("epsilon", &DatasetGrasp::epsilon)
      .def_readonly("volume", &DatasetGrasp::volume)
      .def_readonly("force_closure", &DatasetGrasp::forceClosure)
      .def_property_readonly(
          "held",
          [](const DatasetGrasp& g) -> py::object {
            if (g.held < 0) return py::none();
            return py::bool_(g.held == 1);
          },
          "True or False once validated; None when the dataset was not validated.")
      .def_property_readonly(
          "validation",
          [](const DatasetGrasp& g) {
            py::list directions;
            for (const DatasetDirection& d : g.validation) {
              py::dict entry;
              entry["direction"] = toArray(d.direction);
              entry["held"] = d.tried ? py::object(py::bool_(d.held)) : py::object(py::none());
              entry["tried"] = d.tried;
              entry["slip_mm"] = d.slip;
              entry["turn_deg"] = d.turn * 180.0 / M_PI;
              entry["seconds"] = d.seconds;
              entry["failed"] = d.failed;
              directions.append(entry);
            }
            return directions;
          },
          "The validation's 6 directions (+x, -x, +y, -y, +z, -z; object frame) as "
          "graspkit.validate gives them; empty when not validated. In batch, validation ends at "
          "the "
          "first direction let go by default: the others are not tried (tried False, held None).")
      .def_property_readonly("contact_points",
                             [](const DatasetGrasp& g) { return points(g.contactPoints); })
      .def_property_readonly("contact_normals",
                             [](const DatasetGrasp& g) { return points(g.contactNormals); })
      .def("__repr__", [](const DatasetGrasp& g) {
        return fmt::format("<graspkit.DatasetGrasp epsilon {:.6g}, volume {:.6g}>", g.epsilon,
                           g.volume);
      });
}

void bindDatasetClass(py::module_& m) {
  py::class_<GraspDataset>(m, "Dataset", "One object's grasp dataset (docs/dataset.md).")
      .def_readonly("object_file", &GraspDataset::objectFile)
      .def_readonly("object_name", &GraspDataset::objectName)
      .def_readonly("object_mass", &GraspDataset::objectMass, "Grams.")
      .def_readonly("hand_file", &GraspDataset::handFile)
      .def_readonly("hand_name", &GraspDataset::handName)
      .def_readonly("engine_version", &GraspDataset::engineVersion)
      .def_readonly("seed", &GraspDataset::seed)
      .def_readonly("grasps", &GraspDataset::grasps)
      .def(
          "save",
          [](const GraspDataset& d, const std::filesystem::path& file) {
            saveGraspDataset(d, file);
          },
          py::arg("file"),
          "Writes the dataset as an HDF5 file, atomically; load_dataset reads it back whole.")
      .def("__len__", [](const GraspDataset& d) { return d.grasps.size(); })
      .def("__repr__", [](const GraspDataset& d) {
        return fmt::format("<graspkit.Dataset {} with {}: {} grasps>", d.objectName, d.handName,
                           d.grasps.size());
      });
}

}  // namespace

void bindDatasets(py::module_& m) {
  bindDatasetGrasp(m);
  bindDatasetClass(m);
  m.def(
      "load_dataset",
      [](const std::filesystem::path& file) {
        py::gil_scoped_release release;
        return loadGraspDataset(file);
      },
      py::arg("file"), "Reads a grasp dataset file (`graspkit batch` writes them).");
  const DatasetRequest defaults;
  m.def(
      "plan_dataset",
      [](const std::filesystem::path& hand, const std::filesystem::path& object, int grasps,
         std::optional<std::int64_t> steps, std::optional<double> seconds, std::uint64_t seed,
         bool validate, double validate_seconds, bool validate_all_directions,
         std::vector<std::filesystem::path> roots, std::vector<std::filesystem::path> package_path,
         std::string palm) {
        DatasetRequest request;
        request.hand = hand;
        request.object = object;
        LoadArguments load;
        load.roots = std::move(roots);
        load.packagePath = std::move(package_path);
        load.palm = std::move(palm);
        request.load = load.options();
        request.grasps = grasps;
        request.steps = steps;
        request.seconds = seconds;
        request.seed = seed;
        request.validate = validate;
        request.validateSeconds = validate_seconds;
        request.validateAllDirections = validate_all_directions;
        return withWarnings([&] {
          py::gil_scoped_release release;
          return host::planDataset(request);
        });
      },
      py::arg("hand"), py::arg("object"), py::kw_only(), py::arg("grasps") = defaults.grasps,
      py::arg("steps") = py::none(), py::arg("seconds") = py::none(),
      py::arg("seed") = defaults.seed, py::arg("validate") = defaults.validate,
      py::arg("validate_seconds") = defaults.validateSeconds,
      py::arg("validate_all_directions") = defaults.validateAllDirections,
      py::arg("roots") = std::vector<std::filesystem::path>{},
      py::arg("package_path") = std::vector<std::filesystem::path>{}, py::arg("palm") = "",
      "Plans one object's dataset as `graspkit batch` does for each object: the hand over the "
      "object at the origin, simann, the best `grasps` closed, measured and (validate=True) "
      "labelled (validation stops at a grasp's first direction let go unless "
      "validate_all_directions). Budget: steps (default 40000) or seconds. Save it with "
      "Dataset.save.");
  const ObjectGeneratorOptions generator;
  m.def(
      "generate_object",
      [](const std::filesystem::path& folder, std::size_t index, std::uint64_t seed,
         double min_size, double max_size, double density, const std::string& material,
         const std::vector<std::string>& kinds) {
        ObjectGeneratorOptions options;
        options.seed = seed;
        options.minSize = min_size;
        options.maxSize = max_size;
        options.density = density * 1e-3;  // g/cm^3 -> g/mm^3
        options.material = parseNamed<Material>(material, "material");
        if (!kinds.empty()) {
          options.kinds.clear();
          for (const std::string& kind : kinds)
            options.kinds.push_back(parseNamed<ObjectKind>(kind, "object kind"));
        }
        const host::SavedObject saved = host::saveGeneratedObject(folder, options, index);
        py::dict d;
        d["name"] = saved.name;
        d["file"] = saved.file.string();
        d["kind"] = std::string(nameOf(saved.kind));
        d["mass"] = saved.mass;
        d["shape"] = saved.shape;
        return d;
      },
      py::arg("folder"), py::arg("index"), py::kw_only(), py::arg("seed") = generator.seed,
      py::arg("min_size") = generator.minSize, py::arg("max_size") = generator.maxSize,
      py::arg("density") = generator.density * 1e3,
      py::arg("material") = std::string(nameOf(generator.material)),
      py::arg("kinds") = std::vector<std::string>{},
      "Writes object `index` of the set `seed` describes into `folder` as `graspkit objects` "
      "does (NAME.off and NAME.xml) -> {name, file, kind, mass, shape}. Sizes in mm, density in "
      "g/cm^3; kinds from box, cylinder, sphere, superquadric, convex_hull (default: all, in "
      "turn).");
}

}  // namespace graspkit::python
