#pragma once
// The plugin API's names, kept in sb for plugins. Each harness folder's code
// lives in its own namespace (core/ in sb::core, plugin/ in sb::plugin, gl/ in
// sb::gl: harness/README.md), but a plugin written against API version 3 or
// before names them as sb::Scene, sb::Technique, sb::int_param, or, inside a
// namespace of its own under sb (sb::my_family), unqualified. These
// using-declarations keep every such name reachable in sb, so that its source
// builds unchanged; plugin/registry.h, the header every plugin includes for
// its entry point, includes this one. Harness code names the folder
// namespaces (core::Scene) and never relies on these.
//
// Only names go here, never definitions: a name added to the API is declared
// in its folder's namespace, then listed below.

#include "core/counter_rng.h"
#include "core/error.h"
#include "core/install_layout.h"
#include "core/params.h"
#include "core/scene.h"
#include "gl/gpu_scene.h"
#include "plugin/derived_data.h"
#include "plugin/need_data.h"
#include "plugin/needs.h"
#include "plugin/plugin_identity.h"
#include "plugin/registry.h"
#include "plugin/silhouette_edges.h"
#include "plugin/technique.h"

namespace sb {

// core/
using core::AlphaMode;
using core::AnalyticShape;
using core::AreaLight;
using core::as_map_size;
using core::bool_param;
using core::Bounds;
using core::Camera;
using core::check_param_value;
using core::choice_param;
using core::data_dirs;
using core::Decides;
using core::deciding;
using core::default_plugin_dir;
using core::executable_dir;
using core::ExitCode;
using core::extra_plugin_dirs;
using core::fit_clip_planes;
using core::float_param;
using core::InputError;
using core::InputFile;
using core::int_param;
using core::JobError;
using core::kExitBadInput;
using core::kExitInternal;
using core::kExitJobsFailed;
using core::kExitOk;
using core::kSplitMix64Gamma;
using core::Mesh;
using core::odd;
using core::Params;
using core::ParamSpec;
using core::ParamType;
using core::path_param;
using core::resolve_params;
using core::sample_alpha;
using core::Scene;
using core::splitmix64;
using core::splitmix64_mix;
using core::string_param;
using core::TextPosition;
using core::TextureImage;
using core::to_string;
using core::uniform_float;
using core::unit_float;
using core::with_sentinel;

// gl/
using gl::DrawInfo;
using gl::GpuScene;
using gl::MeshDrawFlags;

// plugin/
using plugin::CasterAdjacency;
using plugin::CasterEdges;
using plugin::DerivedData;
using plugin::FrameInputs;
using plugin::identify_plugin;
using plugin::kPluginApiVersion;
using plugin::MeshEdge;
namespace need = plugin::need;
using plugin::NeedProvider;
using plugin::Needs;
using plugin::PlanarReceiver;
using plugin::PluginIdentity;
using plugin::PluginLoadFailure;
using plugin::Registry;
using plugin::SilhouetteEdges;
using plugin::Technique;
using plugin::TechniqueInfo;

}  // namespace sb
