#pragma once
// Models are imported in a process of their own (model_import.cpp): assimp
// parses files a mod hands it, and Debian's assimp 5.2.5 crashes on some
// (a texture line before the first material of an .mtl: a null
// dereference) and hangs on others (a damaged PLY header), both found by
// the model fuzzer. Neither is ours to fix, and a game that dies or hangs
// on a mod's file is worse than one that refuses it. So render::loadModel
// runs tumble_model_import (model_import_main.cpp: this file's
// loadModelInThisProcess on the path), reads the model it writes as bytes,
// checks every index and size, and turns a crash or a hang (killed after
// ModelLoadOptions::importTimeout_s) into an error naming the file.
#include <memory>
#include <string>

#include "core/result.h"
#include "render/model.h"

namespace tumble::render {

/// The file exists and the options are valid (the parent checks this before
/// it starts the importer, for a quick, clear message).
Status checkModelRequest(const std::string& path, const ModelLoadOptions& options);
/// assimp and stb_image in this process (model_loader.cpp). Warnings go to
/// Model::warnings, never to the log: the importer process has none.
Result<std::shared_ptr<const Model>> loadModelInThisProcess(const std::string& path, const ModelLoadOptions& options);

/// What tumble_model_import writes: a model or the error, as bytes.
std::string encodeImportResult(const Result<std::shared_ptr<const Model>>& result);
/// Reads those bytes back, checking each count against the bytes left and
/// every index against what it indexes (a damaged answer is an error, never
/// a model that draws out of bounds). `path` starts the messages.
Result<std::shared_ptr<const Model>> decodeImportResult(const std::string& bytes, const std::string& path);

/// The importer executable: $TUMBLE_MODEL_IMPORTER if set, else
/// tumble_model_import next to the running program, else in the build's
/// bin folder.
std::string modelImporterPath();

}  // namespace tumble::render
