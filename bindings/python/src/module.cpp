// The graspkit._graspkit extension module; graspkit/__init__.py re-exports it.

#include "graspkit/base/version.hpp"
#include "python_support.hpp"

PYBIND11_MODULE(_graspkit, m) {
  namespace gp = graspkit::python;
  m.doc() = "graspkit: GraspIt!'s grasp analysis and planning, from Python.";
  m.def(
      "version", [] { return std::string(graspkit::engineVersion()); }, "The engine's version.");
  gp::bindErrors(m);
  gp::installWarningHandler(m);
  gp::bindPoses(m);
  gp::bindWorld(m);
  gp::bindRobot(m);
  gp::bindGrasp(m);
  gp::bindRays(m);
  gp::bindPlanning(m);
  gp::bindPlugins(m);
  gp::bindDynamics(m);
  gp::bindDatasets(m);
}
