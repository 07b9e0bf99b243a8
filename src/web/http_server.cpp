// holoray_http.so: `holoray web --serve DIR` (api::serve_folder), a static
// server for the light-field page through cpp-httplib. A module loaded on
// first use, so that no other command loads cpp-httplib's libraries
// (OpenSSL, zlib, brotli).
#include <httplib.h>

#include <cstdio>
#include <string>

extern "C" __attribute__((visibility("default"))) int holoray_serve_folder(const char* dir, const char* host, int port,
                                                                          void (*listening)(const char*, void*),
                                                                          void* user, char* error, size_t error_size) {
  httplib::Server server;
  if (!server.set_mount_point("/", dir)) {
    std::snprintf(error, error_size, "'%s' is not a folder", dir);
    return 1;
  }
  // Every reply fresh: a page rewritten by `holoray web` is seen on reload.
  server.set_post_routing_handler([](const httplib::Request&, httplib::Response& r) { r.set_header("Cache-Control", "no-store"); });
  const int bound = port == 0 ? server.bind_to_any_port(host) : (server.bind_to_port(host, port) ? port : -1);
  if (bound <= 0) {
    std::snprintf(error, error_size, "cannot listen on %s:%d (in use, or not an address of this machine)", host, port);
    return 1;
  }
  const std::string shown = std::string(host).find(':') != std::string::npos ? "[" + std::string(host) + "]" : host;
  listening(("http://" + shown + ":" + std::to_string(bound) + "/").c_str(), user);
  if (!server.listen_after_bind()) {
    std::snprintf(error, error_size, "the server on %s:%d stopped", host, bound);
    return 1;
  }
  return 0;
}
