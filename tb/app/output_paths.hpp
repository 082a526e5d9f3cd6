// Output paths, checked before any work starts: every command of `raycore` that writes files
// calls check_outputs() with its inputs and outputs first, so that an unwritable output, an
// output that would overwrite an input, or two outputs naming the same file end the command with
// a clear message (exit status 1) before minutes of work, and nothing is written.
#pragma once

#include <string>
#include <vector>

#include "scene.hpp"

namespace rc::app {

// A file a command reads or writes, with the option that named it ("-o", "--hits", "input").
struct NamedPath {
  std::string option;
  std::string path;
};

// Throws rc::scene::Error naming the option and the path when an output (an empty path is no
// output) is a directory, lies in a directory that does not exist or cannot be written, exists and
// cannot be written, is the same file as one of `inputs`, or is the same file as another output.
// Creates and writes nothing.
void check_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

// Throws rc::scene::Error when `dir` cannot be a directory to write into: it exists and is not a
// directory, or its nearest existing parent is not a writable directory. Creates nothing.
void check_output_dir(const NamedPath& dir);

// The files a loaded scene was read from, as inputs for check_outputs(): a JSON scene's own file,
// its meshes' files and their MTL files (built-in scenes and meshes have none).
std::vector<NamedPath> scene_inputs(const rc::scene::Scene& scene);

// Whether two paths name the same file: the same inode when both exist, else the same
// normalised absolute path (symbolic links in the existing part resolved).
bool same_file(const std::string& a, const std::string& b);

}  // namespace rc::app
