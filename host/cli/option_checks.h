// Checks of command-line values that the render settings table (render/parameters.h)
// does not cover, shared by the subcommands. Each throws InputError naming the option
// and the value, before any work.
#pragma once
#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "render/settings.h"
#include "scene/scene.h"

namespace tessera::cli {

/// A validator for a real-valued option that must be a finite decimal number
/// ("--exposure nan: must be a finite number").
CLI::Validator finite_number(const std::string& option);

/// A validator for a real-valued option that must be finite and within (lo, hi] when
/// `lo_open`, else [lo, hi]; the message says the range in words ("--speed 0: must be a
/// finite number > 0 and <= 1e+12"), never a machine bound such as DBL_MAX.
CLI::Validator finite_number_in(const std::string& option, double lo, double hi, bool lo_open);

/// A validator for an integer option within [lo, hi]: "--screenshot-window-frame -1: must be
/// an integer in 0..999999". It rewrites the text in canonical decimal ("010" -> "10"), so
/// add it with Option::transform (a check's rewrite is dropped and CLI11 reads "010" as octal).
CLI::Validator integer_in(const std::string& option, long long lo, long long hi);

/// Every option and positional of `cmd` that was given with an empty value:
/// "--out '': must not be empty".
void reject_empty_values(const CLI::App& cmd);

/// Before parsing the command line `args` (argv without the program name): an option of
/// the named subcommand of `app` that takes a value, followed by another of its options,
/// throws InputError "--stats-json: needs a value (the next word, --out, is an option)".
/// CLI11 would take the option name as the value, and the word after it as the scene.
void reject_options_as_values(const CLI::App& app, const std::vector<std::string>& args);

/// --data-dir, when given (not empty), must name an existing directory.
void check_data_dir(const std::string& data_dir);

/// Prints each of the scene loader's notes (Scene::notes: what it changed without an
/// error, such as an MTL Kd above 1 clamped) to stderr as "tessera: note: <note>".
void print_scene_notes(const std::vector<std::string>& notes);

/// An EXR output path given to `option` ("--out", "--screenshot") must name a file whose
/// extension is ".exr", in lower case. InputError "--out x.EXR: must end in .exr (lower
/// case)", or for "dir/.exr" (a hidden name, no extension) "...: needs a file name before
/// .exr", for "dir/" "...: ends in '/'; name the file, e.g. dir/image.exr", and for an
/// existing directory "...: is a directory; name the file, ...".
void require_exr_name(const std::string& option, const std::filesystem::path& path);

/// The output a command writes when its option is not given: out/<scene file's name,
/// without .json><suffix> ("out/box.exr" for box.json and ".exr"), relative to the
/// working directory. From the file's name, not the scene's "name" key: a copy of a scene
/// file renders to its own image, and a key cannot send an output outside out/.
std::filesystem::path default_output(const Scene& scene, const std::string& suffix);

/// An output file of the run, with what the messages call it ("--out", "--stats-json",
/// "--out's PNG preview", "--out's checkpoint").
struct OutputFile {
    std::filesystem::path path;
    std::string role;
};

/// Checks every output before any work: a file name; not a directory or other
/// non-regular file; its directory exists or can be made (the nearest existing ancestor
/// is a directory); no two outputs the same file, and none of them one of `inputs` (the
/// scene file first, then the files it loads: Scene::inputs; a command's other inputs).
/// InputError "<role> <path>: is a directory", "...: is the scene file", "...: would
/// replace an input of this run, <file>". Creates nothing.
void check_outputs(const std::vector<OutputFile>& outputs, const std::vector<std::filesystem::path>& inputs);

/// Checks that each output's directory is writable, or, where it does not exist yet, its
/// nearest existing ancestor (so that it can be made), by creating and removing a
/// temporary file there. Creates no directory: the writers make them when they first
/// write (image/atomic_file.h), so a run that fails before it writes leaves nothing
/// behind. RuntimeError naming the output, the directory and the OS reason.
void check_output_directories(const std::vector<OutputFile>& outputs);

/// Settings of the igi family that make no sense for this scene, for render and view
/// alike: `--march-steps 0` on a scene with a medium (the igi family ray-marches it), and
/// `--components` that compute no light there (EffectPlan::components_compute: the image
/// would be the emitters alone). Render checks them for an igi-family --method only;
/// `switches_methods` (the viewer, whose M key reaches the igi family from any --method)
/// checks them whatever the method. InputError naming the option, its value and `scene_path`.
void check_scene_options(const RenderSettings& s, const std::string& components, const Scene& scene,
                         const std::filesystem::path& scene_path, bool switches_methods = false);

}  // namespace tessera::cli
