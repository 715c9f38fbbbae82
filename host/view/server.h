// The viewer's HTTP server: 127.0.0.1 only, one request at a time, GET only; the handler answers each path.
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

namespace voxcd::view {

struct HttpRequest {
  std::string path;   // percent-decoded, without the query
  std::string query;  // after '?', percent-decoded ("" when none)
};

struct HttpResponse {
  int status = 200;
  std::string type = "text/plain; charset=utf-8";
  std::string body;
};

class HttpServer {
 public:
  // Listens on 127.0.0.1:port (0: a free port the system chooses). std::runtime_error naming the port when it
  // cannot (in use, not allowed).
  explicit HttpServer(uint16_t port);
  ~HttpServer();
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;
  uint16_t port() const { return port_; }
  // Answers requests with `handler` until `seconds` have passed (0: until SIGINT or SIGTERM). A handler's exception
  // becomes a 400 answer with its message; a malformed request a 400; anything but GET a 405.
  void serve(const std::function<HttpResponse(const HttpRequest&)>& handler, double seconds);

 private:
  void answer(int client, const std::function<HttpResponse(const HttpRequest&)>& handler);
  int fd_ = -1;
  uint16_t port_ = 0;
};

}  // namespace voxcd::view
