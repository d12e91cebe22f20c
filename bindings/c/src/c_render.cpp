// Pictures of a world, as graspkit render draws them, and generated objects, as graspkit
// objects writes them.

#include <algorithm>

#include <fmt/format.h>

#include "c_api_support.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/host/object_task.hpp"
#include "graspkit/render/image.hpp"
#include "graspkit/render/render.hpp"

using namespace graspkit;
using namespace graspkit::c_api;

extern "C" {

graspkit_status graspkit_render_options_default(graspkit_render_options* options) {
  return guarded([&] {
    const RenderRequest defaults;
    graspkit_render_options& o = *require(options, "options");
    o = graspkit_render_options{};
    o.width = defaults.width;
    o.height = defaults.height;
    o.camera = "auto";
    o.contacts = 0;
    o.samples = defaults.samples;
  });
}

graspkit_status graspkit_world_render(const graspkit_world* world,
                                      const graspkit_render_options* options, uint8_t* rgb,
                                      size_t capacity, const char* png) {
  return guarded([&] {
    const World& w = require(world, "world")->world;
    graspkit_render_options o;
    graspkit_render_options_default(&o);
    if (options) o = *options;
    RenderRequest request;
    request.width = o.width;
    request.height = o.height;
    request.samples = o.samples;
    if (o.width < 1 || o.height < 1)
      throw Failure{GRASPKIT_ERROR_INVALID_ARGUMENT,
                    fmt::format("a {} x {} picture: both sides must be >= 1", o.width, o.height)};
    const std::size_t needed =
        static_cast<std::size_t>(o.width) * static_cast<std::size_t>(o.height) * 3;
    if (capacity < needed)
      throw Failure{GRASPKIT_ERROR_BUFFER_TOO_SMALL,
                    fmt::format("rgb holds {} bytes; a {} x {} picture needs {}", capacity, o.width,
                                o.height, needed)};
    require(rgb, "rgb");
    const std::vector<BodyRef> focus = handAndObject(w);
    request.camera =
        namedView(w, o.camera ? o.camera : "auto", focus, static_cast<double>(o.width) / o.height);
    const GraspSubject subject = graspSubject(w);
    if (o.contacts && subject.hand && subject.object)
      request.contacts = analyzeGrasp(w, *subject.hand, *subject.object).contacts;
    const Image image = render(w, request);
    std::copy(image.rgb.begin(), image.rgb.end(), rgb);
    if (png) writePng(image, png);
  });
}

graspkit_status graspkit_generate_object(const char* folder, uint64_t seed, size_t index,
                                         char* xml_path, size_t capacity, size_t* length) {
  return guarded([&] {
    ObjectGeneratorOptions options;
    options.seed = seed;
    const host::SavedObject saved =
        host::saveGeneratedObject(require(folder, "folder"), options, index);
    copyString(saved.file.string(), xml_path, capacity, length);
  });
}

}  // extern "C"
