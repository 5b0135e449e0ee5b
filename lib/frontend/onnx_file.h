#pragma once
// Reading an ONNX model file for OpenCV DNN with errors that name the file: the model
// detectors and the range labeler share it. The reading call itself (cv::dnn::readNetFromONNX)
// is passed in, so that the DNN headers stay in the .cpp files that run the networks.
#include <filesystem>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>

namespace slide::frontend {

// read(path) for an existing file; std::runtime_error "<path>: no such model file (named by
// <yaml>)" when it is missing, "<path>: not a readable ONNX model (...)" when reading fails or
// gives an empty network.
template <typename Read>
auto readOnnxFile(const std::string& path, const std::string& yaml, Read read) -> decltype(read(path)) {
  if (!std::filesystem::is_regular_file(path)) throw std::runtime_error(path + ": no such model file (named by " + yaml + ")");
  try {
    auto net = read(path);
    if (net.empty()) throw std::runtime_error(path + ": not a readable ONNX model (empty network)");
    return net;
  } catch (const cv::Exception& e) {
    throw std::runtime_error(path + ": not a readable ONNX model (" + e.what() + ")");
  }
}

}  // namespace slide::frontend
