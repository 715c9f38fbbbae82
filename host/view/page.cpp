#include "voxcd/host/view/page.h"

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace voxcd::view {

namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw std::runtime_error("view: " + path + " is missing: the page needs three.js from Debian's libjs-three "
                             "(apt-get install libjs-three), or VOXCD_THREE_DIR naming a copy of it");
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::string three_file(const std::string& url) {
  if (url == "three.min.js") return read_file(three_dir() + "/three.min.js");
  return read_file(three_dir() + "/examples/js/controls/OrbitControls.js");
}

std::string own_file(const std::string& name) {
  for (const auto& f : detail::page_files())
    if (name == f.name) return std::string(reinterpret_cast<const char*>(f.data), f.size);
  return {};
}

std::string mime(const std::string& path) {
  if (path.size() >= 3 && path.compare(path.size() - 3, 3, ".js") == 0) return "text/javascript; charset=utf-8";
  if (path.size() >= 4 && path.compare(path.size() - 4, 4, ".css") == 0) return "text/css; charset=utf-8";
  return "text/html; charset=utf-8";
}

// `s` safe inside a <script> element: "</script" would close it (three.js and our files have none in code; in
// the data it can only be inside a JSON string, where "<\/" reads as "</").
std::string script_safe(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    out += s[i];
    if (s[i] == '<' && i + 7 < s.size() && s[i + 1] == '/' && (s[i + 2] == 's' || s[i + 2] == 'S')) out += '\\';
  }
  return out;
}

}  // namespace

std::string three_dir() {
  const char* d = std::getenv("VOXCD_THREE_DIR");
  return d && *d ? d : "/usr/share/javascript/three";
}

void check_three() {
  three_file("three.min.js");
  three_file("OrbitControls.js");
}

std::optional<HttpResponse> page_file(const std::string& path) {
  if (path == "/" || path == "/index.html") {
    std::string html = own_file("index.html");
    const std::string mark = "<!--VOXCD_DATA-->";
    html.erase(html.find(mark), mark.size());
    return HttpResponse{200, mime(".html"), html};
  }
  if (path.rfind("/three/", 0) == 0 && (path == "/three/three.min.js" || path == "/three/OrbitControls.js"))
    return HttpResponse{200, mime(path), three_file(path.substr(7))};
  if (path.rfind("/view/", 0) == 0) {
    std::string body = own_file(path.substr(6));
    if (!body.empty()) return HttpResponse{200, mime(path), body};
  }
  return std::nullopt;
}

std::string self_contained_html(const std::string& data_json) {
  std::string html = own_file("index.html");
  // Each <script src="X"></script> becomes the script itself.
  const std::string open = "<script src=\"", close = "\"></script>";
  for (size_t at = html.find(open); at != std::string::npos; at = html.find(open, at)) {
    const size_t end = html.find(close, at);
    const std::string src = html.substr(at + open.size(), end - at - open.size());
    const std::string code = src.rfind("three/", 0) == 0 ? three_file(src.substr(6)) : own_file(src.substr(5));
    const std::string inlined = "<script>" + script_safe(code) + "</script>";
    html.replace(at, end + close.size() - at, inlined);
    at += inlined.size();
  }
  const std::string mark = "<!--VOXCD_DATA-->";
  html.replace(html.find(mark), mark.size(), "<script>window.VOXCD_DATA = " + script_safe(data_json) + ";</script>");
  return html;
}

}  // namespace voxcd::view
