// graspkit.World, graspkit.load_world and graspkit.Body: building worlds, saving them, looking
// bodies and robots up, and what a body is (pose, mass properties, mesh).

#include <fmt/format.h>

#include "graspkit/base/enum_names.hpp"
#include "graspkit/collision/collision.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/host/subject.hpp"
#include "graspkit/io/graspit/body_file.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/material.hpp"
#include "graspkit/render/render.hpp"
#include "python_support.hpp"

namespace graspkit::python {

Body& BodyView::body() const {
  if (!world->followRemovals(index, seen))
    throw py::index_error("the body was removed from its world");
  auto& bodies = world->world.bodies();
  if (index < 0 || index >= static_cast<int>(bodies.size()))
    throw py::index_error(fmt::format("body {} no longer exists", index));
  return bodies[static_cast<std::size_t>(index)];
}

const Robot& RobotView::robot() const {
  if (index < 0 || index >= world->world.robotCount())
    throw py::index_error(fmt::format("robot {} no longer exists", index));
  return world->world.robot(index);
}

BodyRef toBodyRef(const WorldHandle& world, const py::handle& body, const char* what) {
  if (py::isinstance<BodyView>(body)) {
    const auto& view = body.cast<const BodyView&>();
    if (view.world.get() != &world)
      throw py::value_error(fmt::format("{}: the body belongs to another world", what));
    view.body();
    return BodyRef::body(view.index);
  }
  if (py::isinstance<py::str>(body)) {
    const auto name = body.cast<std::string>();
    if (auto found = findBodyRef(world.world, name)) return *found;
    throw py::value_error(fmt::format("{}: the world has no body named '{}'", what, name));
  }
  throw py::type_error(fmt::format("{}: a Body or a body name expected", what));
}

int toRobotIndex(const WorldHandle& world, const py::handle& robot) {
  if (robot.is_none()) {
    try {
      return host::defaultHand(world.world);
    } catch (const Error& e) {
      throw py::value_error(e.what());
    }
  }
  if (py::isinstance<RobotView>(robot)) {
    const auto& view = robot.cast<const RobotView&>();
    if (view.world.get() != &world)
      throw py::value_error("robot: the robot belongs to another world");
    view.robot();
    return view.index;
  }
  if (py::isinstance<py::str>(robot)) {
    const auto name = robot.cast<std::string>();
    if (auto found = world.world.findRobot(name)) return *found;
    throw py::value_error(fmt::format("the world has no robot named '{}'", name));
  }
  const int index = robot.cast<int>();
  if (index < 0 || index >= world.world.robotCount())
    throw py::index_error(
        fmt::format("robot {} out of range (the world has {})", index, world.world.robotCount()));
  return index;
}

LoadOptions LoadArguments::options() const {
  LoadOptions options;
  options.roots = roots;
  options.genericRobotFallback = genericRobots;
  options.packagePaths = packagePath;
  options.urdfPalm = palm;
  options.srdf = srdf;
  if (!urdfMaterial.empty()) options.urdfMaterial = parseNamed<Material>(urdfMaterial, "material");
  for (const auto& [link, material] : linkMaterials)
    options.urdfLinkMaterials[link] = parseNamed<Material>(material, "material");
  for (const auto& [dof, sign] : close) {
    if (dof < 0 || (sign != "+" && sign != "-"))
      throw py::value_error(fmt::format(
          "close: {{{}: '{}'}} is not {{dof: '+' or '-'}} (dof a 0-based index)", dof, sign));
    options.closingDirections[dof] = sign == "+" ? 1 : -1;
  }
  return options;
}

namespace {

// Files are held by absolute path, so that a world saved elsewhere names them correctly (relative
// to its own folder when they lie below it, else absolute).
BodyView addBody(const WorldPtr& world, const std::filesystem::path& relative,
                 const py::object& pose, BodyKind kind) {
  const std::filesystem::path file = std::filesystem::absolute(relative);
  Body body;
  body.model = loadBodyFile(file, world->cache.get());
  body.kind = kind;
  body.setPose(pose.is_none() ? Transform::Identity() : toTransform(pose));
  // The load's warnings reach Python before the world changes: a filter that turns them into
  // errors leaves the world as it was.
  flushWarnings();
  return BodyView{world, world->world.addBody(std::move(body))};
}

RobotView addRobot(const WorldPtr& world, const std::filesystem::path& relative,
                   const py::object& pose, const LoadArguments& load) {
  const std::filesystem::path file = std::filesystem::absolute(relative);
  const Transform t = pose.is_none() ? Transform::Identity() : toTransform(pose);
  Robot robot(loadRobotFile(file, load.options(), world->cache.get()));
  flushWarnings();  // before the world changes, as in addBody
  return withWarnings([&] {
    const int index = world->world.addRobot(std::move(robot), file);
    world->world.setRobotPose(index, t);
    return RobotView{world, index};
  });
}

py::array_t<double> vertices(const Body& body, const std::string& frame) {
  if (frame != "world" && frame != "body")
    throw py::value_error(fmt::format("frame '{}': \"world\" or \"body\" expected", frame));
  const auto& mesh = body.model->mesh;
  const std::size_t n = mesh ? mesh->vertices.size() : 0;
  py::array_t<double> out({static_cast<py::ssize_t>(n), py::ssize_t{3}});
  auto a = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < n; ++i) {
    const Vector3 p = frame == "world" ? Vector3(body.pose * mesh->vertices[i]) : mesh->vertices[i];
    for (int k = 0; k < 3; ++k) a(static_cast<py::ssize_t>(i), k) = p[k];
  }
  return out;
}

py::array_t<std::int64_t> triangles(const Body& body) {
  const auto& mesh = body.model->mesh;
  const std::size_t n = mesh ? mesh->triangles.size() : 0;
  py::array_t<std::int64_t> out({static_cast<py::ssize_t>(n), py::ssize_t{3}});
  auto a = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) a(static_cast<py::ssize_t>(i), k) = mesh->triangles[i][k];
  return out;
}

void bindBody(py::module_& m) {
  py::class_<BodyView>(m, "Body",
                       "A free body of a world: an obstacle or a graspable object. A view: it "
                       "reads and writes its world.")
      .def_property_readonly("name", [](const BodyView& b) { return b.body().name; })
      .def_property_readonly(
          "index", [](const BodyView& b) { return b.index; },
          "Its 0-based index among the world's bodies.")
      .def_property_readonly("kind",
                             [](const BodyView& b) { return std::string(nameOf(b.body().kind)); })
      .def_property_readonly("is_dynamic", [](const BodyView& b) { return b.body().isDynamic(); })
      .def_property(
          "pose", [](const BodyView& b) { return toMatrix(b.body().pose); },
          [](const BodyView& b, const py::object& pose) { b.body().setPose(toTransform(pose)); },
          "The body frame in the world, a 4x4 matrix in mm.")
      .def_property_readonly("file",
                             [](const BodyView& b) { return b.body().model->file.string(); })
      .def_property_readonly(
          "material",
          [](const BodyView& b) { return std::string(nameOf(b.body().model->material)); })
      .def_property_readonly(
          "mass", [](const BodyView& b) { return b.body().model->mass; }, "Grams.")
      .def_property_readonly(
          "cog", [](const BodyView& b) { return toArray(b.body().model->cog); },
          "The centre of gravity in the body frame, mm.")
      .def_property_readonly(
          "inertia",
          [](const BodyView& b) {
            py::array_t<double> out({3, 3});
            auto a = out.mutable_unchecked<2>();
            for (int r = 0; r < 3; ++r)
              for (int c = 0; c < 3; ++c) a(r, c) = b.body().model->inertia(r, c);
            return out;
          },
          "Per unit mass, about the CoG, in body axes (mm^2), as the Body file gives it.")
      .def_property_readonly(
          "max_radius", [](const BodyView& b) { return b.body().model->maxRadius; },
          "The largest CoG-to-vertex distance, mm (the torque scale of the "
          "grasp wrench space).")
      .def_property_readonly("triangle_count",
                             [](const BodyView& b) {
                               const auto& mesh = b.body().model->mesh;
                               return mesh ? mesh->triangleCount() : std::size_t{0};
                             })
      .def(
          "vertices",
          [](const BodyView& b, const std::string& frame) { return vertices(b.body(), frame); },
          py::arg("frame") = "world", "The mesh's vertices, (N, 3) in mm, world or body frame.")
      .def(
          "triangles", [](const BodyView& b) { return triangles(b.body()); },
          "The mesh's triangles, (M, 3) vertex indices, counter-clockwise seen from outside.")
      .def("__repr__", [](const BodyView& b) {
        return fmt::format("<graspkit.Body '{}' ({})>", b.body().name, nameOf(b.body().kind));
      });
}

// World.render: the picture is drawn on a clone, with the GIL released.
py::array_t<std::uint8_t> renderWorld(const WorldPtr& w, int width, int height,
                                      const std::string& camera, bool contacts, int samples,
                                      const py::object& out) {
  RenderRequest request;
  request.width = width;
  request.height = height;
  request.samples = samples;
  const World world = w->world.clone();
  Image image;
  {
    py::gil_scoped_release release;
    const std::vector<BodyRef> focus = handAndObject(world);
    request.camera = namedView(world, camera, focus, static_cast<double>(width) / height);
    const GraspSubject subject = graspSubject(world);
    if (contacts && subject.hand && subject.object)
      request.contacts = analyzeGrasp(world, *subject.hand, *subject.object).contacts;
    image = render(world, request);
  }
  if (!out.is_none()) writePng(image, py::cast<std::filesystem::path>(out));
  py::array_t<std::uint8_t> pixels({static_cast<py::ssize_t>(image.height),
                                    static_cast<py::ssize_t>(image.width), py::ssize_t{3}});
  std::copy(image.rgb.begin(), image.rgb.end(), pixels.mutable_data());
  return pixels;
}

void bindWorldClass(py::module_& m) {
  py::class_<WorldHandle, WorldPtr>(m, "World", "Bodies and robots in one frame (mm).")
      .def(py::init([] { return std::make_shared<WorldHandle>(); }), "An empty world.")
      .def(
          "add_object",
          [](const WorldPtr& w, const std::filesystem::path& file, const py::object& pose) {
            return addBody(w, file, pose, BodyKind::Graspable);
          },
          py::arg("file"), py::arg("pose") = py::none(),
          "Adds a graspable body from a Body XML or a bare mesh (.iv, .wrl, .off, .stl, .obj, "
          ".ply).")
      .def(
          "add_obstacle",
          [](const WorldPtr& w, const std::filesystem::path& file, const py::object& pose) {
            return addBody(w, file, pose, BodyKind::Obstacle);
          },
          py::arg("file"), py::arg("pose") = py::none(), "Adds a static body.")
      .def(
          "add_robot",
          [](const WorldPtr& w, const std::filesystem::path& file, const py::object& pose,
             bool generic_robots, std::vector<std::filesystem::path> package_path, std::string palm,
             std::map<int, std::string> close) {
            LoadArguments load;
            load.genericRobots = generic_robots;
            load.packagePath = std::move(package_path);
            load.palm = std::move(palm);
            load.close = std::move(close);
            return addRobot(w, file, pose, load);
          },
          py::arg("file"), py::arg("pose") = py::none(), py::kw_only(),
          py::arg("generic_robots") = false,
          py::arg("package_path") = std::vector<std::filesystem::path>{}, py::arg("palm") = "",
          py::arg("close") = std::map<int, std::string>{},
          "Adds a robot from a GraspIt! robot XML, a URDF or an MJCF file; its type's plugin is "
          "loaded on demand. package_path, palm and close as load_world's.")
      .def(
          "remove_body",
          [](const WorldPtr& w, const py::object& body) {
            const BodyRef ref = toBodyRef(*w, body, "body");
            if (ref.kind != BodyRef::Kind::Body)
              throw py::value_error("only obstacles and graspable bodies can be removed");
            w->removeBody(ref.index);
          },
          py::arg("body"),
          "Removes an obstacle or graspable body (a Body or its name). Body views of later bodies "
          "follow; views of the removed one raise IndexError.")
      .def(
          "save",
          [](WorldHandle& w, const std::filesystem::path& file) {
            w.save(file);
            w.file = std::filesystem::absolute(file);
          },
          py::arg("file"),
          "Writes a GraspIt! world XML, atomically; files below its folder are named relatively.")
      .def(
          "clone", [](const WorldHandle& w) { return std::make_shared<WorldHandle>(w.clone()); },
          "An independent copy (meshes are shared, read-only).")
      .def_property_readonly(
          "file",
          [](const WorldHandle& w) -> py::object {
            if (w.file.empty()) return py::none();
            return py::str(w.file.string());
          },
          "Where the world was loaded from or last saved; None for a new world.")
      .def_property_readonly("bodies",
                             [](const WorldPtr& w) {
                               std::vector<BodyView> out;
                               for (int i = 0; i < static_cast<int>(w->world.bodies().size()); ++i)
                                 out.push_back({w, i});
                               return out;
                             })
      .def(
          "body",
          [](const WorldPtr& w, const std::string& name) {
            const auto& bodies = w->world.bodies();
            for (std::size_t i = 0; i < bodies.size(); ++i)
              if (bodies[i].name == name) return BodyView{w, static_cast<int>(i)};
            throw py::key_error(fmt::format("the world has no body named '{}'", name));
          },
          py::arg("name"))
      .def_property_readonly("robots",
                             [](const WorldPtr& w) {
                               std::vector<RobotView> out;
                               for (int i = 0; i < w->world.robotCount(); ++i)
                                 out.push_back({w, i});
                               return out;
                             })
      .def(
          "robot",
          [](const WorldPtr& w, const py::object& which) {
            return RobotView{w, toRobotIndex(*w, which)};
          },
          py::arg("which") = py::none(),
          "A robot by 0-based index or name; without an argument the world's first hand.")
      .def("render", &renderWorld, py::kw_only(), py::arg("width") = RenderRequest{}.width,
           py::arg("height") = RenderRequest{}.height, py::arg("camera") = "auto",
           py::arg("contacts") = false, py::arg("samples") = RenderRequest{}.samples,
           py::arg("out") = py::none(),
           "A ray-cast picture, as `graspkit render` draws it: a (height, width, 3) uint8 array; "
           "`out` also writes it as a PNG. camera: auto, world, iso, +x, -x, +y, -y, +z, -z; "
           "contacts marks the first hand's contacts with the first graspable body.")
      .def(
          "collides", [](const WorldPtr& w) { return anyCollision(w->world, {}); },
          "Whether any two bodies that may collide intersect.")
      .def("__repr__", [](const WorldHandle& w) {
        return fmt::format("<graspkit.World: {} bodies, {} robots>", w.world.bodies().size(),
                           w.world.robotCount());
      });

  m.def(
      "load_world",
      [](const std::filesystem::path& file, std::vector<std::filesystem::path> roots,
         bool generic_robots, std::vector<std::filesystem::path> package_path, std::string palm,
         std::string urdf_material, std::map<std::string, std::string> link_materials,
         std::map<int, std::string> close, std::optional<std::filesystem::path> srdf) {
        const LoadArguments load{std::move(roots),         generic_robots,
                                 std::move(package_path),  std::move(palm),
                                 std::move(urdf_material), std::move(link_materials),
                                 std::move(close),         srdf.value_or(std::filesystem::path{})};
        return withWarnings([&] {
          auto handle =
              std::make_shared<WorldHandle>(host::WorldSession::load(file, load.options()));
          handle->file = std::filesystem::absolute(file);
          return handle;
        });
      },
      py::arg("file"), py::kw_only(), py::arg("roots") = std::vector<std::filesystem::path>{},
      py::arg("generic_robots") = false,
      py::arg("package_path") = std::vector<std::filesystem::path>{}, py::arg("palm") = "",
      py::arg("urdf_material") = "",
      py::arg("link_materials") = std::map<std::string, std::string>{},
      py::arg("close") = std::map<int, std::string>{}, py::arg("srdf") = py::none(),
      "Loads a GraspIt! world, robot or body file, a URDF or MJCF hand, or a bare mesh into a new "
      "World. A world's <filename>s are looked up below `roots` first, then $GRASPKIT_ROOT, "
      "$GRASPIT, then the file's folder and its parents. For URDF hands, as `graspkit`'s flags: "
      "package_path (folders holding package:// packages), palm (the palm link), urdf_material "
      "and link_materials ({link: material}), close ({dof: '+' or '-'}: the way a DOF closes) and "
      "srdf.");
}

}  // namespace

void bindWorld(py::module_& m) {
  bindBody(m);
  bindWorldClass(m);
}

}  // namespace graspkit::python
