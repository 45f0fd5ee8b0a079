// glTF 2.0 assets as trade scenes (see gltf.hpp).
#include "saagen/measure/gltf.hpp"

#include "saagen/reference/saa.hpp"

#include <stb/stb_image.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include <tiny_gltf.h>

namespace saagen::measure {

using ref::cross;
using ref::dot;
using ref::kPi;
using ref::length;
using ref::normalize;

namespace {

// Column-major 4 x 4 matrix, as glTF stores node.matrix.
struct Mat4 {
  std::array<double, 16> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  double at(int row, int column) const { return m[static_cast<std::size_t>(column * 4 + row)]; }
  double& at(int row, int column) { return m[static_cast<std::size_t>(column * 4 + row)]; }
  Vec3 point(Vec3 p) const {
    return {at(0, 0) * p.x + at(0, 1) * p.y + at(0, 2) * p.z + at(0, 3), at(1, 0) * p.x + at(1, 1) * p.y + at(1, 2) * p.z + at(1, 3),
            at(2, 0) * p.x + at(2, 1) * p.y + at(2, 2) * p.z + at(2, 3)};
  }
  Vec3 vector(Vec3 v) const {
    return {at(0, 0) * v.x + at(0, 1) * v.y + at(0, 2) * v.z, at(1, 0) * v.x + at(1, 1) * v.y + at(1, 2) * v.z,
            at(2, 0) * v.x + at(2, 1) * v.y + at(2, 2) * v.z};
  }
  // The inverse transpose of the upper 3 x 3 applied to a normal: the cofactor matrix (the
  // inverse transpose times the determinant, whose positive or negative scale normalize()
  // removes up to the sign; the sign is the determinant's, taken out below).
  Vec3 normal(Vec3 n) const {
    const Vec3 c0{at(0, 0), at(1, 0), at(2, 0)}, c1{at(0, 1), at(1, 1), at(2, 1)}, c2{at(0, 2), at(1, 2), at(2, 2)};
    const Vec3 r0 = cross(c1, c2), r1 = cross(c2, c0), r2 = cross(c0, c1);  // columns of the cofactor matrix
    const double det = dot(c0, r0);
    const Vec3 out = n.x * r0 + n.y * r1 + n.z * r2;
    return det < 0.0 ? -1.0 * out : out;
  }
};

Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0.0;
      for (int k = 0; k < 4; ++k) s += a.at(i, k) * b.at(k, j);
      r.at(i, j) = s;
    }
  return r;
}

// A node's local matrix: `matrix`, or T R S (glTF 2.0 Sec. 3.5.3).
Mat4 local_matrix(const tinygltf::Node& node) {
  Mat4 out;
  if (node.matrix.size() == 16) {
    std::copy(node.matrix.begin(), node.matrix.end(), out.m.begin());
    return out;
  }
  double x = 0, y = 0, z = 0, w = 1;
  if (node.rotation.size() == 4) {
    x = node.rotation[0], y = node.rotation[1], z = node.rotation[2], w = node.rotation[3];
    const double n = std::sqrt(x * x + y * y + z * z + w * w);
    if (n > 0.0) x /= n, y /= n, z /= n, w /= n;
  }
  const double s[3] = {node.scale.size() == 3 ? node.scale[0] : 1.0, node.scale.size() == 3 ? node.scale[1] : 1.0,
                       node.scale.size() == 3 ? node.scale[2] : 1.0};
  // Rotation matrix of the unit quaternion (x, y, z, w).
  const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                          {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                          {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.at(i, j) = r[i][j] * s[j];
  if (node.translation.size() == 3)
    for (int i = 0; i < 3; ++i) out.at(i, 3) = node.translation[static_cast<std::size_t>(i)];
  return out;
}

std::string one_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) text.pop_back();
  std::string out;
  for (char c : text) {
    if (c == '\r') continue;
    if (c == '\n') {
      out += "; ";
      continue;
    }
    out += c;
  }
  return out;
}

// Control characters (and DEL) as \xNN, so that text from an asset cannot drive the terminal.
std::string printable(std::string_view text) {
  std::string out;
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) {
      char escaped[5];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      out += escaped;
    } else {
      out += c;
    }
  }
  return out;
}

// What is wrong with the asset's JSON before it is parsed (nlohmann's parse and tinygltf's
// conversion recurse per nesting level and take ~0.3 KB per value): deeper than the limit, more
// values than the limit, or an integer beyond 32 bits outside "extras" (tinygltf truncates such
// an index to int: 2^40 would read as accessor 0). Empty when none; else "line L: ...".
std::string json_problem(std::string_view text, const GltfLimits& limits) {
  int depth = 0, extras_depth = -1;
  std::size_t values = 0;
  bool after_key = false;  // the next value is an object member's, named `key`
  std::string key;
  auto at_line = [&](std::size_t offset, const std::string& what) {
    return "line " + std::to_string(1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n')) + ": " + what;
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ',' || c == ':') continue;
    const bool value_of_extras = after_key && key == "extras";
    after_key = false;
    if (++values > limits.max_json_values)
      return at_line(i, "more than " + std::to_string(limits.max_json_values) + " JSON values, beyond the limit");
    if (c == '"') {
      const std::size_t start = ++i;
      while (i < text.size() && text[i] != '"') i += text[i] == '\\' ? 2 : 1;
      std::size_t next = i + 1;
      while (next < text.size() && (text[next] == ' ' || text[next] == '\t' || text[next] == '\n' || text[next] == '\r')) ++next;
      if (next < text.size() && text[next] == ':') {
        key.assign(text.substr(start, std::min(i, text.size()) - start));
        after_key = true;
        --values;  // a member's name is not a value
      }
    } else if (c == '{' || c == '[') {
      if (++depth > limits.max_json_depth)
        return at_line(i, "JSON nested deeper than " + std::to_string(limits.max_json_depth) + " levels, beyond the limit");
      if (value_of_extras && extras_depth < 0) extras_depth = depth;
    } else if (c == '}' || c == ']') {
      if (depth == extras_depth) extras_depth = -1;
      --depth;
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      std::size_t end = i;
      bool integer = true;
      while (end < text.size() && text[end] != '\0' && std::strchr("+-0123456789.eE", text[end]) != nullptr) {
        if (text[end] == '.' || text[end] == 'e' || text[end] == 'E') integer = false;
        ++end;
      }
      const std::string number(text.substr(i, end - i));
      if (integer && extras_depth < 0 && !value_of_extras) {
        errno = 0;
        const long long value = std::strtoll(number.c_str(), nullptr, 10);
        if (errno == ERANGE || value > std::numeric_limits<int>::max() || value < std::numeric_limits<int>::min())
          return at_line(i, "the integer " + number + " is beyond the 32 bits glTF's indices and counts take here");
      }
      i = end - 1;
    }
  }
  return {};
}

// Positions (after the node transforms) are at most this in magnitude, so that sums, products and
// areas of them stay finite (a box translated by 1e308 has centroids of inf).
constexpr double kMaxCoordinate = 1e100;
std::string coordinates_limit() { return "1e100"; }

bool is_bounded(Vec3 p) { return std::fabs(p.x) <= kMaxCoordinate && std::fabs(p.y) <= kMaxCoordinate && std::fabs(p.z) <= kMaxCoordinate; }

std::string coordinates(Vec3 p) {
  std::ostringstream s;
  s.precision(6);
  s << p.x << ", " << p.y << ", " << p.z;
  return s.str();
}

std::string sanitized_stem(const std::string& path) {
  std::string stem = std::filesystem::path(path).stem().string();
  for (char& c : stem)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) c = '_';
  return stem.empty() ? std::string("asset") : stem;
}

// The loading state: the model, the file's path for messages, the limits and the texture cache.
class Loader {
 public:
  Loader(const std::string& path, const GltfLimits& limits) : path_(path), limits_(limits) {}

  [[noreturn]] void fail(const std::string& what) const { throw GltfError(path_ + ": " + what); }

  GltfAsset load() {
    read_model();
    check_required_extensions();
    GltfAsset asset;
    asset.path = path_;
    asset.files = files_;
    asset.name = sanitized_stem(path_);
    for (std::size_t i = 0; i < model_.materials.size(); ++i) asset.materials.push_back(material(static_cast<int>(i)));
    default_material_ = static_cast<int>(asset.materials.size());
    GltfMaterial fallback;
    fallback.name = "(default)";
    asset.materials.push_back(std::move(fallback));
    traverse_scene(asset);
    if (triangles_.empty()) fail("no triangles in the scene's meshes; nothing to render");
    asset.primitives = static_cast<int>(object_material_.size());
    asset.object_material = object_material_;
    asset.generated_tangent_primitives = generated_tangents_;
    asset.bounds_lo = {1e300, 1e300, 1e300};
    asset.bounds_hi = {-1e300, -1e300, -1e300};
    for (const MeshVertex& v : vertices_) {
      asset.bounds_lo = {std::min(asset.bounds_lo.x, v.position.x), std::min(asset.bounds_lo.y, v.position.y),
                         std::min(asset.bounds_lo.z, v.position.z)};
      asset.bounds_hi = {std::max(asset.bounds_hi.x, v.position.x), std::max(asset.bounds_hi.y, v.position.y),
                         std::max(asset.bounds_hi.z, v.position.z)};
    }
    check_bounds(asset.bounds_lo, asset.bounds_hi);
    asset.camera = camera_;
    if (light_) {
      asset.light = *light_;
      if (asset.light->kind == Light::Kind::point) {
        const Vec3 d = asset.light->vector - 0.5 * (asset.bounds_lo + asset.bounds_hi);
        asset.light->intensity = dot(d, d);  // irradiance 1 at the bounds' centre
      }
    }
    auto surfaces = std::make_shared<SurfaceMaterials>();
    std::ostringstream description;
    description.precision(17);
    for (std::size_t object = 0; object < object_material_.size(); ++object) {
      const GltfMaterial& m = asset.materials[static_cast<std::size_t>(object_material_[object])];
      SurfaceTextures t;
      t.normal_map = m.normal_map;
      t.roughness_map = m.roughness_map;
      if (m.clearcoat && m.clearcoat_factor > 0.0) {
        t.coat = m.clearcoat_factor;
        t.coat_map = m.clearcoat_map;
      }
      t.anisotropy = m.anisotropic_lobe;
      if (t.normal_map || t.roughness_map || t.coat > 0.0 || t.anisotropy) {
        description << "o" << object << ":" << (t.normal_map ? t.normal_map->describe() : "-") << ","
                    << (t.roughness_map ? t.roughness_map->describe() : "-");
        if (t.coat > 0.0) description << ",coat=" << t.coat << "," << (t.coat_map ? t.coat_map->describe() : "-");
        if (t.anisotropy) description << "," << t.anisotropy->describe();
        description << ";";
      }
      surfaces->by_object.push_back(std::move(t));
    }
    surfaces->description = description.str();
    asset.surfaces = std::move(surfaces);
    asset.coat_surfaces = coat_surfaces(asset);
    asset.mesh = std::make_shared<const TriangleMesh>("gltf:" + asset.name, std::move(vertices_), std::move(triangles_),
                                                      std::move(triangle_objects_));
    return asset;
  }

 private:
  // The coat lobe's textures and weights per object (null when no material has a coat).
  std::shared_ptr<const SurfaceMaterials> coat_surfaces(const GltfAsset& asset) const {
    bool any = false;
    auto coats = std::make_shared<SurfaceMaterials>();
    std::ostringstream description;
    description.precision(17);
    description << "coat;";
    for (std::size_t object = 0; object < object_material_.size(); ++object) {
      const GltfMaterial& m = asset.materials[static_cast<std::size_t>(object_material_[object])];
      SurfaceTextures t;
      t.weight = m.clearcoat ? m.clearcoat_factor : 0.0;
      if (m.clearcoat && m.clearcoat_factor > 0.0) {
        any = true;
        t.normal_map = m.clearcoat_normal_map;
        t.roughness_map = m.clearcoat_roughness_map;
        t.weight_map = m.clearcoat_map;
      }
      description << "o" << object << ":" << t.weight << "," << (t.normal_map ? t.normal_map->describe() : "-") << ","
                  << (t.roughness_map ? t.roughness_map->describe() : "-") << "," << (t.weight_map ? t.weight_map->describe() : "-") << ";";
      coats->by_object.push_back(std::move(t));
    }
    if (!any) return nullptr;
    coats->description = description.str();
    return coats;
  }

  // The box the camera frames and the light is placed from: finite in size, and not one point.
  void check_bounds(Vec3 lo, Vec3 hi) const {
    const Vec3 extent = hi - lo;
    if (!std::isfinite(extent.x) || !std::isfinite(extent.y) || !std::isfinite(extent.z))
      fail("the scene's bounds (" + coordinates(lo) + ") - (" + coordinates(hi) + ") are larger than a double can hold");
    if (extent.x == 0.0 && extent.y == 0.0 && extent.z == 0.0)
      fail("every vertex lies at one point (" + coordinates(lo) + "); nothing to render");
  }

  // --- file -------------------------------------------------------------------------------

  // tinygltf's image callback: the header is read and checked (a size beyond the limit is refused
  // before anything is decoded), the encoded bytes kept; an image is decoded only when a material
  // uses it (decoded_image), after the texel budget has been checked.
  static bool load_image(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int, const unsigned char* bytes,
                         int size, void* user) {
    auto* self = static_cast<Loader*>(user);
    if (image->bufferView >= 0) {  // tinygltf checks the indices (its buffers and views are read first), not the range
      const tinygltf::BufferView& view = self->model_.bufferViews[static_cast<std::size_t>(image->bufferView)];
      const std::size_t buffer_size = self->model_.buffers[static_cast<std::size_t>(view.buffer)].data.size();
      if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset) {
        if (err)
          *err += "image " + std::to_string(index) + ": buffer view " + std::to_string(image->bufferView) + " runs past its buffer's " +
                  std::to_string(buffer_size) + " bytes";
        return false;
      }
    }
    int w = 0, h = 0, components = 0;
    if (!stbi_info_from_memory(bytes, size, &w, &h, &components)) {
      if (err) *err += "image " + std::to_string(index) + " ('" + image->uri + "') is not a PNG or JPEG stb_image can decode";
      return false;
    }
    if (w > self->limits_.max_texture_size || h > self->limits_.max_texture_size) {
      if (err)
        *err += "image " + std::to_string(index) + " ('" + image->uri + "') is " + std::to_string(w) + "x" + std::to_string(h) +
                ", beyond the limit of " + std::to_string(self->limits_.max_texture_size) + " texels per side";
      return false;
    }
    image->width = w;
    image->height = h;
    image->component = components;
    EncodedImage& encoded = self->encoded_[index];
    if (image->bufferView >= 0) {  // inside a buffer that stays in the model: no copy
      encoded.data = bytes;
      encoded.size = static_cast<std::size_t>(size);
    } else {
      encoded.owned.assign(bytes, bytes + size);
      encoded.data = encoded.owned.data();
      encoded.size = encoded.owned.size();
    }
    return true;
  }

  // The path of an external file as tinygltf joined it: the asset's folder, then the URI.
  std::string folder_prefix() const { return base_dir_.empty() ? std::string() : (base_dir_.back() == '/' ? base_dir_ : base_dir_ + "/"); }

  // Why a URI may not be opened: an absolute one, or a relative one that leaves the asset's
  // folder. Empty when it may.
  std::string uri_problem(const std::string& path) const {
    const std::string prefix = folder_prefix();
    if (path.compare(0, prefix.size(), prefix) != 0) return "is outside the asset's folder";
    const std::filesystem::path uri(path.substr(prefix.size()));
    if (uri.is_absolute()) return "is an absolute URI; an asset's files are named relative to its folder";
    const std::filesystem::path normal = uri.lexically_normal();
    if (normal.empty() || *normal.begin() == "..") return "leaves the asset's folder; an asset's files must lie in its folder or below";
    return {};
  }

  // tinygltf searches the asset's folder, then the current directory: only the first is the asset's.
  bool is_current_directory_fallback(const std::string& path) const {
    return !base_dir_.empty() && base_dir_ != "." && path.compare(0, folder_prefix().size(), folder_prefix()) != 0;
  }

  // tinygltf's file reader for the asset's external buffers and images, behind the checks a
  // hostile URI needs: inside the asset's folder, only a regular file (a FIFO would block the
  // read, /dev/zero never ends), at most max_file_bytes, and max_total_bytes with the others.
  static bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    auto* self = static_cast<Loader*>(user);
    if (std::string problem = self->uri_problem(path); !problem.empty()) {
      if (self->uri_refusal_.empty()) self->uri_refusal_ = "'" + path + "' " + problem;
      if (err) *err += "'" + path + "' " + problem;
      return false;
    }
    if (const std::string problem = self->file_problem(path); !problem.empty()) {
      if (err) *err += "'" + path + "' " + problem;
      return false;
    }
    if (!tinygltf::ReadWholeFile(out, err, path, nullptr)) return false;
    self->files_.push_back(path);
    return true;
  }

  // Whether a file exists, without opening it (tinygltf's own FileExists opens it for reading,
  // which blocks on a FIFO); a URI that may not be opened "exists", so that the reader refuses it
  // by name.
  static bool file_exists(const std::string& path, void* user) {
    const auto* self = static_cast<const Loader*>(user);
    if (self->is_current_directory_fallback(path)) return false;
    if (!self->uri_problem(path).empty()) return true;
    std::error_code error;
    return std::filesystem::exists(path, error);
  }

  // The URI as written (tinygltf's default expands ~ and $VARIABLES with wordexp).
  static std::string expand_file_path(const std::string& path, void*) { return path; }

  // Why a file cannot be read as part of the asset; empty when it can. Counts its bytes into the
  // asset's total.
  std::string file_problem(const std::string& path) {
    std::error_code error;
    const auto status = std::filesystem::status(path, error);
    if (error || !std::filesystem::exists(status)) return "does not exist";
    if (!std::filesystem::is_regular_file(status)) return "is not a regular file";
    const std::uintmax_t size = std::filesystem::file_size(path, error);
    if (error) return "cannot be sized";
    if (size > limits_.max_file_bytes)
      return "is " + std::to_string(size) + " bytes, beyond the limit of " + std::to_string(limits_.max_file_bytes);
    if (size > limits_.max_total_bytes - std::min(total_bytes_, limits_.max_total_bytes))
      return "brings the asset's files to " + std::to_string(total_bytes_ + size) + " bytes, beyond the limit of " +
             std::to_string(limits_.max_total_bytes) + " in all";
    total_bytes_ += size;
    return {};
  }

  // The asset's file, read whole (file_problem checked it first).
  std::string read_asset_file() {
    std::ifstream in(path_, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) fail("cannot be read");
    files_.push_back(path_);
    return bytes;
  }

  // The JSON of a .glb (its first chunk, when the container's header holds together; tinygltf
  // reports a broken container), or of a .gltf (the whole file).
  static std::string_view json_text(std::string_view bytes, bool binary) {
    if (!binary) return bytes;
    auto u32 = [&](std::size_t at) {
      std::uint32_t v = 0;
      std::memcpy(&v, bytes.data() + at, 4);
      return v;
    };
    if (bytes.size() < 20 || bytes.substr(0, 4) != "glTF" || u32(16) != 0x4E4F534Au || u32(12) > bytes.size() - 20) return {};
    return bytes.substr(20, u32(12));
  }

  void check_json(std::string_view json) const {
    if (json.size() > limits_.max_json_bytes)
      fail("its JSON is " + std::to_string(json.size()) + " bytes, beyond the limit of " + std::to_string(limits_.max_json_bytes));
    if (const std::string problem = json_problem(json, limits_); !problem.empty()) fail(problem);
  }

  void read_model() {
    if (const std::string problem = file_problem(path_); !problem.empty())
      fail(problem + (problem == "does not exist" ? " (a .gltf or .glb asset is expected)" : ""));
    const std::string extension = std::filesystem::path(path_).extension().string();
    const bool binary = extension == ".glb" || extension == ".GLB";
    if (!binary && extension != ".gltf" && extension != ".GLTF") fail("not a .gltf or .glb file");
    const std::string bytes = read_asset_file();
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) fail("too large for tinygltf");
    check_json(json_text(bytes, binary));
    const std::size_t slash = path_.find_last_of('/');
    base_dir_ = slash == std::string::npos ? std::string() : path_.substr(0, slash);
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&Loader::load_image, this);
    loader.SetFsCallbacks({&Loader::file_exists, &Loader::expand_file_path, &Loader::read_whole_file, &tinygltf::WriteWholeFile, this});
    std::string err, warn;
    const auto size = static_cast<unsigned int>(bytes.size());
    const bool ok =
        binary ? loader.LoadBinaryFromMemory(&model_, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()), size, base_dir_)
               : loader.LoadASCIIFromString(&model_, &err, &warn, bytes.data(), size, base_dir_);
    if (!uri_refusal_.empty()) fail(uri_refusal_);  // an image's, which tinygltf only warns about
    if (!ok) fail("not a readable glTF 2.0 asset (tinygltf: " + one_line(err.empty() ? "no message" : err) + ")");
    if (model_.asset.version.rfind("2.", 0) != 0)
      fail("asset.version is '" + printable(model_.asset.version) + "'; this loader reads glTF 2.0 (version \"2.0\")");
    warnings_ = one_line(warn);
  }

  void check_required_extensions() const {
    static const std::set<std::string> supported{"KHR_materials_clearcoat", "KHR_materials_anisotropy", "KHR_lights_punctual"};
    for (const std::string& name : model_.extensionsRequired)
      if (!supported.count(name)) fail("requires extension " + name + ", which this loader does not implement");
  }

  // --- accessors ------------------------------------------------------------------------------

  struct View {
    const unsigned char* data = nullptr;
    std::size_t stride = 0;
    std::size_t count = 0;
    int component_type = 0;
    int components = 0;
    bool normalized = false;
  };

  View view(int index, const std::string& what) const {
    if (index < 0 || index >= static_cast<int>(model_.accessors.size()))
      fail(what + ": accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& a = model_.accessors[static_cast<std::size_t>(index)];
    const std::string name = what + " (accessor " + std::to_string(index) + ")";
    if (a.sparse.isSparse) fail(name + ": sparse accessors are not supported");
    if (a.bufferView < 0 || a.bufferView >= static_cast<int>(model_.bufferViews.size())) fail(name + ": no buffer view");
    if (a.count > 3 * limits_.max_vertices)
      fail(name + ": " + std::to_string(a.count) + " elements, beyond the limit of " + std::to_string(3 * limits_.max_vertices));
    const tinygltf::BufferView& bv = model_.bufferViews[static_cast<std::size_t>(a.bufferView)];
    if (bv.buffer < 0 || bv.buffer >= static_cast<int>(model_.buffers.size())) fail(name + ": buffer view without a buffer");
    const tinygltf::Buffer& buffer = model_.buffers[static_cast<std::size_t>(bv.buffer)];
    const int component_size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
    const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
    if (component_size <= 0 || components <= 0) fail(name + ": unknown component or element type");
    const std::size_t element = static_cast<std::size_t>(component_size) * static_cast<std::size_t>(components);
    const std::size_t stride = bv.byteStride ? bv.byteStride : element;
    if (stride < element) fail(name + ": byteStride " + std::to_string(stride) + " is shorter than an element");
    if (bv.byteOffset > buffer.data.size() || bv.byteLength > buffer.data.size() - bv.byteOffset)
      fail(name + ": buffer view " + std::to_string(a.bufferView) + " runs past its buffer's " + std::to_string(buffer.data.size()) +
           " bytes");
    if (a.count > 0 && (a.byteOffset > bv.byteLength || (a.count - 1) * stride + element > bv.byteLength - a.byteOffset))
      fail(name + ": " + std::to_string(a.count) + " elements run past buffer view " + std::to_string(a.bufferView));
    View v;
    v.data = buffer.data.data() + bv.byteOffset + a.byteOffset;
    v.stride = stride;
    v.count = a.count;
    v.component_type = a.componentType;
    v.components = components;
    v.normalized = a.normalized;
    return v;
  }

  // Component c of element i as a float: floats as stored, normalised integers mapped to
  // [0, 1] or [-1, 1] (glTF 2.0 Sec. 3.11, "normalized" accessors).
  static double component(const View& v, std::size_t i, int c) {
    const unsigned char* p = v.data + i * v.stride;
    switch (v.component_type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float f;
        std::memcpy(&f, p + 4 * c, 4);
        return f;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return p[c] / 255.0;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t s;
        std::memcpy(&s, p + 2 * c, 2);
        return s / 65535.0;
      }
      default:
        return 0.0;
    }
  }

  View attribute(const tinygltf::Primitive& primitive, const std::string& name, const std::string& where, int components,
                 bool allow_normalized) const {
    const View v = view(primitive.attributes.at(name), where + " " + name);
    const bool is_float = v.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT;
    const bool is_unorm = v.normalized && (v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                           v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
    if (v.components != components || !(is_float || (allow_normalized && is_unorm)))
      fail(where + " " + name + ": " + std::to_string(v.components) + " components of type " + std::to_string(v.component_type) +
           " (expected " + std::to_string(components) + (allow_normalized ? " floats or normalised unsigned integers)" : " floats)"));
    return v;
  }

  std::vector<std::uint32_t> indices(const tinygltf::Primitive& primitive, std::size_t vertex_count, const std::string& where) const {
    std::vector<std::uint32_t> out;
    if (primitive.indices < 0) {
      out.resize(vertex_count);
      for (std::size_t i = 0; i < vertex_count; ++i) out[i] = static_cast<std::uint32_t>(i);
      return out;
    }
    const View v = view(primitive.indices, where + " indices");
    if (v.components != 1) fail(where + " indices: not scalars");
    if (v.count > 3 * limits_.max_triangles + 2)
      fail(where + " indices: " + std::to_string(v.count) + " indices, beyond the limit of " + std::to_string(limits_.max_triangles) +
           " triangles");
    out.resize(v.count);
    for (std::size_t i = 0; i < v.count; ++i) {
      const unsigned char* p = v.data + i * v.stride;
      std::uint32_t index = 0;
      if (v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
        index = p[0];
      } else if (v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
        std::uint16_t s;
        std::memcpy(&s, p, 2);
        index = s;
      } else if (v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
        std::memcpy(&index, p, 4);
      } else {
        fail(where + " indices: component type " + std::to_string(v.component_type) + " is not an unsigned integer");
      }
      if (index >= vertex_count)
        fail(where + " indices: index " + std::to_string(index) + " beyond the " + std::to_string(vertex_count) + " vertices");
      out[i] = index;
    }
    return out;
  }

  // --- textures -------------------------------------------------------------------------------

  // What every use of a texture must satisfy (checked on each use: a map built for one use is
  // shared only with uses that pass these too).
  void check_texture_use(int texture, int texcoord, const tinygltf::ExtensionMap& extensions, const std::string& what) const {
    if (texture < 0 || texture >= static_cast<int>(model_.textures.size()))
      fail(what + ": texture " + std::to_string(texture) + " does not exist");
    if (texcoord != 0) fail(what + ": uses TEXCOORD_" + std::to_string(texcoord) + "; only TEXCOORD_0 is loaded");
    if (extensions.count("KHR_texture_transform")) fail(what + ": KHR_texture_transform is not supported");
    const tinygltf::Texture& t = model_.textures[static_cast<std::size_t>(texture)];
    if (t.sampler >= 0 && t.sampler < static_cast<int>(model_.samplers.size())) {
      const tinygltf::Sampler& s = model_.samplers[static_cast<std::size_t>(t.sampler)];
      if (s.wrapS != TINYGLTF_TEXTURE_WRAP_REPEAT || s.wrapT != TINYGLTF_TEXTURE_WRAP_REPEAT)
        fail(what + ": sampler " + std::to_string(t.sampler) + " does not wrap with REPEAT, the only addressing the MIP chains implement");
    }
    if (t.source < 0 || t.source >= static_cast<int>(model_.images.size()))
      fail(what + ": texture " + std::to_string(texture) + " has no PNG or JPEG source image");
  }

  // The decoded image behind a texture (check_texture_use first), checked for what the MIP chains
  // need; its texels counted into the budget of the maps built, before it is decoded.
  const tinygltf::Image& texture_image(int texture, const std::string& what) {
    const int source = model_.textures[static_cast<std::size_t>(texture)].source;
    tinygltf::Image& image = model_.images[static_cast<std::size_t>(source)];
    const std::string name = "image " + std::to_string(source) + (image.uri.empty() ? std::string() : " ('" + printable(image.uri) + "')");
    const auto encoded = encoded_.find(source);
    if (image.image.empty() && encoded == encoded_.end()) fail(what + ": " + name + " could not be read (missing or undecodable file)");
    auto pot = [](int v) { return v > 0 && (v & (v - 1)) == 0; };
    if (!pot(image.width) || !pot(image.height))
      fail(what + ": " + name + " is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
           "; the MIP chains are exact 2x2 box means and need power-of-two sizes (resize it)");
    const std::size_t texels = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
    if (texels_ + texels > limits_.max_texels)
      fail(what + ": " + name + " brings the decoded textures to " + std::to_string(texels_ + texels) + " texels, beyond the limit of " +
           std::to_string(limits_.max_texels));
    texels_ += texels;
    if (image.image.empty()) {
      std::string err, warn;
      const bool decoded =
          tinygltf::LoadImageData(&image, source, &err, &warn, 0, 0, encoded->second.data, static_cast<int>(encoded->second.size), nullptr);
      encoded_.erase(encoded);
      if (!decoded || image.image.empty()) fail(what + ": " + name + " could not be decoded (" + one_line(err) + ")");
    }
    if ((image.bits != 8 && image.bits != 16) || image.component < 1 ||
        image.image.size() < static_cast<std::size_t>(image.width) * image.height * image.component * (image.bits / 8))
      fail(what + ": " + name + " has an unexpected pixel layout");
    return image;
  }

  // The image a texture samples (textures sharing an image share its decoded maps); the texture's
  // own index, negated and offset, when it has none (texture_image then reports it).
  int image_of(int texture) const {
    if (texture < 0 || texture >= static_cast<int>(model_.textures.size())) return -1 - texture;
    const int source = model_.textures[static_cast<std::size_t>(texture)].source;
    return source >= 0 ? source : -1 - texture;
  }

  // Channel c of texel i in [0, 1] (8 or 16 bits; a missing channel reads as the last one).
  static double channel(const tinygltf::Image& image, std::size_t i, int c) {
    const int ch = std::min(c, image.component - 1);
    const std::size_t at = i * static_cast<std::size_t>(image.component) + static_cast<std::size_t>(ch);
    if (image.bits == 16) {
      std::uint16_t s;
      std::memcpy(&s, image.image.data() + 2 * at, 2);
      return s / 65535.0;
    }
    return image.image[at] / 255.0;
  }

  std::shared_ptr<const ScalarMap> green_map(const tinygltf::TextureInfo& info, const std::string& what) {
    return channel_map(info, 1, what);
  }

  // One channel (0 = R, 1 = G) of a texture as a ScalarMap, linear values in [0, 1].
  std::shared_ptr<const ScalarMap> channel_map(const tinygltf::TextureInfo& info, int c, const std::string& what) {
    if (info.index < 0) return nullptr;
    check_texture_use(info.index, info.texCoord, info.extensions, what);
    const std::string key = "c" + std::to_string(c) + "," + std::to_string(image_of(info.index));
    if (auto found = scalar_cache_.find(key); found != scalar_cache_.end()) return found->second;
    const tinygltf::Image& image = texture_image(info.index, what);
    std::vector<double> values(static_cast<std::size_t>(image.width) * image.height);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = channel(image, i, c);
    auto map = std::make_shared<const ScalarMap>(image.width, image.height, std::move(values));
    scalar_cache_[key] = map;
    return map;
  }

  // glTF 2.0 Sec. 3.9.3: scaledNormal = normalize((sample * 2 - 1) * (scale, scale, 1)). A texel
  // whose z is below 1e-3 (a blue channel at or below 128 / 255, or a large scale) is lifted to
  // z = 1e-3 before normalising: the map's normals must face out of the surface.
  std::shared_ptr<const NormalMap> normal_map(int texture, int texcoord, double scale, const tinygltf::ExtensionMap& extensions,
                                              const std::string& what) {
    if (texture < 0) return nullptr;
    check_texture_use(texture, texcoord, extensions, what);
    std::ostringstream key;
    key.precision(17);
    key << "n" << image_of(texture) << "," << scale;
    if (auto found = normal_cache_.find(key.str()); found != normal_cache_.end()) return found->second;
    const tinygltf::Image& image = texture_image(texture, what);
    if (image.component < 3) fail(what + ": a normal texture needs RGB, image has " + std::to_string(image.component) + " channel(s)");
    std::vector<Vec3> normals(static_cast<std::size_t>(image.width) * image.height);
    for (std::size_t i = 0; i < normals.size(); ++i) {
      Vec3 n{(2.0 * channel(image, i, 0) - 1.0) * scale, (2.0 * channel(image, i, 1) - 1.0) * scale, 2.0 * channel(image, i, 2) - 1.0};
      if (!(n.z >= 1e-3)) n.z = 1e-3;
      normals[i] = normalize(n);
    }
    auto map = std::make_shared<const NormalMap>(image.width, image.height, std::move(normals));
    normal_cache_[key.str()] = map;
    return map;
  }

  // --- materials ------------------------------------------------------------------------------

  static constexpr double kHuge = std::numeric_limits<double>::max();

  // A non-negative integer member (an index), -1 when absent; anything else is refused: a
  // fraction, a negative number or one beyond int (1e300 would convert to INT_MIN).
  int index_member(const tinygltf::Value& object, const char* key, const std::string& what) const {
    if (!object.IsObject() || !object.Has(key)) return -1;
    const tinygltf::Value& v = object.Get(key);
    const double value = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
    if (!v.IsNumber() || !(value >= 0.0) || value > std::numeric_limits<int>::max() || value != std::floor(value)) {
      std::ostringstream shown;
      shown.precision(17);
      if (v.IsNumber()) shown << value;
      fail(what + ": " + key + " " + (v.IsNumber() ? shown.str() : std::string("(not a number)")) + " is not an index (an integer from 0)");
    }
    return static_cast<int>(value);
  }

  // A number member within the glTF specification's range [low, high], `fallback` when absent.
  double factor(const tinygltf::Value& object, const char* key, double fallback, double low, double high, const std::string& what) const {
    if (!object.IsObject() || !object.Has(key)) return fallback;
    const tinygltf::Value& v = object.Get(key);
    if (!v.IsNumber()) fail(what + ": " + key + " is not a number");
    return checked_factor(v.GetNumberAsDouble(), key, low, high, what);
  }

  double checked_factor(double value, const char* key, double low, double high, const std::string& what) const {
    if (!(std::isfinite(value) && value >= low && value <= high)) {
      std::ostringstream s;
      s.precision(17);
      s << what << ": " << key << " " << value << " is outside ";
      if (high == kHuge)
        s << "the finite numbers";
      else
        s << "[" << low << ", " << high << "], the glTF specification's range";
      fail(s.str());
    }
    return value;
  }

  // The core material's factors, within the specification's ranges (a clearcoatFactor of 1e308
  // would make every pixel inf and every metric meaningless).
  void check_core_factors(const tinygltf::Material& m, const std::string& what) const {
    const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
    for (double c : pbr.baseColorFactor) checked_factor(c, "baseColorFactor", 0.0, 1.0, what);
    checked_factor(pbr.metallicFactor, "metallicFactor", 0.0, 1.0, what);
    checked_factor(pbr.roughnessFactor, "roughnessFactor", 0.0, 1.0, what);
    for (double c : m.emissiveFactor) checked_factor(c, "emissiveFactor", 0.0, 1.0, what);
    checked_factor(m.normalTexture.scale, "normalTexture.scale", -kHuge, kHuge, what);
    checked_factor(m.occlusionTexture.strength, "occlusionTexture.strength", 0.0, 1.0, what);
    checked_factor(m.alphaCutoff, "alphaCutoff", 0.0, kHuge, what);
  }

  // A textureInfo object inside an extension: (index, texCoord, scale), index -1 when absent.
  struct ExtensionTexture {
    int index = -1;
    int texcoord = 0;
    double scale = 1.0;
    tinygltf::ExtensionMap extensions;
  };
  ExtensionTexture extension_texture(const tinygltf::Value& object, const char* key, const std::string& what) const {
    ExtensionTexture t;
    if (!object.IsObject() || !object.Has(key)) return t;
    if (!object.Get(key).IsObject()) fail(what + " " + key + ": not a textureInfo object");
    const tinygltf::Value& info = object.Get(key);
    const std::string where = what + " " + key;
    t.index = index_member(info, "index", where);
    if (t.index < 0) fail(where + ": no texture index");
    t.texcoord = std::max(0, index_member(info, "texCoord", where));
    t.scale = factor(info, "scale", 1.0, -kHuge, kHuge, where);
    if (info.Has("extensions") && info.Get("extensions").IsObject())
      for (const std::string& name : info.Get("extensions").Keys()) t.extensions[name] = info.Get("extensions").Get(name);
    return t;
  }

  GltfMaterial material(int index) {
    const tinygltf::Material& m = model_.materials[static_cast<std::size_t>(index)];
    const std::string what = "material " + std::to_string(index) + (m.name.empty() ? std::string() : " ('" + printable(m.name) + "')");
    check_core_factors(m, what);
    GltfMaterial out;
    out.name = m.name.empty() ? "material" + std::to_string(index) : m.name;
    out.roughness_factor = m.pbrMetallicRoughness.roughnessFactor;
    out.roughness_map = green_map(m.pbrMetallicRoughness.metallicRoughnessTexture, what + " metallicRoughnessTexture");
    out.normal_scale = m.normalTexture.scale;
    out.normal_map = normal_map(m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.scale, m.normalTexture.extensions,
                                what + " normalTexture");
    if (auto it = m.extensions.find("KHR_materials_clearcoat"); it != m.extensions.end()) {
      const tinygltf::Value& c = it->second;
      out.clearcoat = true;
      const std::string coat_what = what + " KHR_materials_clearcoat";
      out.clearcoat_factor = factor(c, "clearcoatFactor", 0.0, 0.0, 1.0, coat_what);
      out.clearcoat_roughness_factor = factor(c, "clearcoatRoughnessFactor", 0.0, 0.0, 1.0, coat_what);
      const ExtensionTexture roughness = extension_texture(c, "clearcoatRoughnessTexture", coat_what);
      if (roughness.index >= 0) {
        tinygltf::TextureInfo info;
        info.index = roughness.index;
        info.texCoord = roughness.texcoord;
        info.extensions = roughness.extensions;
        out.clearcoat_roughness_map = green_map(info, what + " clearcoatRoughnessTexture");
      }
      const ExtensionTexture coat = extension_texture(c, "clearcoatTexture", coat_what);
      if (coat.index >= 0) {
        tinygltf::TextureInfo info;
        info.index = coat.index;
        info.texCoord = coat.texcoord;
        info.extensions = coat.extensions;
        out.clearcoat_map = channel_map(info, 0, what + " clearcoatTexture");
      }
      const ExtensionTexture normal = extension_texture(c, "clearcoatNormalTexture", coat_what);
      out.clearcoat_normal_scale = normal.scale;
      out.clearcoat_normal_map =
          normal_map(normal.index, normal.texcoord, normal.scale, normal.extensions, what + " clearcoatNormalTexture");
    }
    if (auto it = m.extensions.find("KHR_materials_anisotropy"); it != m.extensions.end()) {
      const tinygltf::Value& a = it->second;
      out.anisotropy = true;
      const std::string anisotropy_what = what + " KHR_materials_anisotropy";
      out.anisotropy_strength = factor(a, "anisotropyStrength", 0.0, 0.0, 1.0, anisotropy_what);
      out.anisotropy_rotation = factor(a, "anisotropyRotation", 0.0, -kHuge, kHuge, anisotropy_what);
      const ExtensionTexture texture = extension_texture(a, "anisotropyTexture", anisotropy_what);
      auto lobe = std::make_shared<Anisotropy>();
      lobe->strength = out.anisotropy_strength;
      lobe->rotation = {std::cos(out.anisotropy_rotation), std::sin(out.anisotropy_rotation)};
      if (texture.index >= 0) {
        tinygltf::TextureInfo info;
        info.index = texture.index;
        info.texCoord = texture.texcoord;
        info.extensions = texture.extensions;
        const std::string where = what + " anisotropyTexture";
        lobe->red = channel_map(info, 0, where);
        lobe->green = channel_map(info, 1, where);
        lobe->blue = channel_map(info, 2, where);
        out.anisotropy_texture = true;
      }
      if (out.anisotropy_strength != 0.0 || out.anisotropy_texture) out.anisotropic_lobe = std::move(lobe);
    }
    has_textures_.push_back(out.roughness_map || out.normal_map || out.clearcoat_roughness_map || out.clearcoat_normal_map ||
                            out.anisotropy_texture);
    return out;
  }

  // --- scene ----------------------------------------------------------------------------------

  std::vector<int> scene_roots() const {
    std::vector<int> roots;
    const int scene = model_.defaultScene >= 0 ? model_.defaultScene : (model_.scenes.empty() ? -1 : 0);
    if (scene >= static_cast<int>(model_.scenes.size())) fail("default scene " + std::to_string(scene) + " does not exist");
    if (scene >= 0) {
      roots = model_.scenes[static_cast<std::size_t>(scene)].nodes;
    } else {
      // No scene: every node that is no other node's child.
      std::vector<bool> child(model_.nodes.size(), false);
      for (const tinygltf::Node& node : model_.nodes)
        for (int c : node.children)
          if (c >= 0 && c < static_cast<int>(child.size())) child[static_cast<std::size_t>(c)] = true;
      for (std::size_t i = 0; i < child.size(); ++i)
        if (!child[i]) roots.push_back(static_cast<int>(i));
    }
    for (int root : roots) check_node(root);
    return roots;
  }

  void check_node(int index) const {
    if (index < 0 || index >= static_cast<int>(model_.nodes.size())) fail("node " + std::to_string(index) + " does not exist");
  }

  // The triangles one instance of a node's mesh adds (from its accessors' counts; 0 where they
  // are broken, which the walk then reports).
  std::size_t mesh_triangles(const tinygltf::Node& node) const {
    if (node.mesh < 0 || node.mesh >= static_cast<int>(model_.meshes.size())) return 0;
    std::size_t total = 0;
    for (const tinygltf::Primitive& primitive : model_.meshes[static_cast<std::size_t>(node.mesh)].primitives) {
      int accessor = primitive.indices;
      if (accessor < 0) {
        const auto position = primitive.attributes.find("POSITION");
        accessor = position == primitive.attributes.end() ? -1 : position->second;
      }
      if (accessor < 0 || accessor >= static_cast<int>(model_.accessors.size())) continue;
      const std::size_t count = model_.accessors[static_cast<std::size_t>(accessor)].count;
      const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
      total += mode == TINYGLTF_MODE_TRIANGLES ? count / 3 : (count >= 3 ? count - 2 : 0);
    }
    return total;
  }

  // The nodes reachable from the roots, parents before children (a cycle is refused).
  std::vector<int> nodes_in_order(const std::vector<int>& roots) const {
    enum class Mark : unsigned char { unseen, open, done };
    std::vector<Mark> mark(model_.nodes.size(), Mark::unseen);
    std::vector<int> finished;                       // children before parents
    std::vector<std::pair<int, std::size_t>> stack;  // node, next child
    for (int root : roots) {
      if (mark[static_cast<std::size_t>(root)] != Mark::unseen) continue;
      stack.push_back({root, 0});
      mark[static_cast<std::size_t>(root)] = Mark::open;
      while (!stack.empty()) {
        auto& [node, next] = stack.back();
        const std::vector<int>& children = model_.nodes[static_cast<std::size_t>(node)].children;
        if (next == children.size()) {
          mark[static_cast<std::size_t>(node)] = Mark::done;
          finished.push_back(node);
          stack.pop_back();
          continue;
        }
        const int child = children[next++];
        check_node(child);
        if (mark[static_cast<std::size_t>(child)] == Mark::open) fail("node " + std::to_string(child) + " is its own ancestor (a cycle)");
        if (mark[static_cast<std::size_t>(child)] == Mark::unseen) {
          mark[static_cast<std::size_t>(child)] = Mark::open;
          stack.push_back({child, 0});
        }
      }
    }
    return {finished.rbegin(), finished.rend()};
  }

  // Counts the scene's node instances (paths from a root: a node listed twice by its parent, or
  // by two parents, is instanced twice, and so is everything below it) and the triangles they
  // instance, refusing either beyond its limit before anything is expanded (40 nodes each listing
  // the next twice are 2^40 instances).
  void check_instance_counts(const std::vector<int>& roots) const {
    const std::vector<int> order = nodes_in_order(roots);
    constexpr std::uint64_t saturated = std::uint64_t{1} << 62;
    auto add = [&](std::uint64_t a, std::uint64_t b) { return std::min(saturated, a + b); };
    std::vector<std::uint64_t> instances(model_.nodes.size(), 0);
    for (int root : roots) instances[static_cast<std::size_t>(root)] = add(instances[static_cast<std::size_t>(root)], 1);
    std::uint64_t visits = 0, triangles = 0;
    for (int node : order) {
      const std::uint64_t n = instances[static_cast<std::size_t>(node)];
      visits = add(visits, n);
      const std::uint64_t per_instance = mesh_triangles(model_.nodes[static_cast<std::size_t>(node)]);
      triangles = per_instance == 0 ? triangles : add(triangles, n > saturated / per_instance ? saturated : n * per_instance);
      for (int child : model_.nodes[static_cast<std::size_t>(node)].children)
        instances[static_cast<std::size_t>(child)] = add(instances[static_cast<std::size_t>(child)], n);
    }
    auto shown = [&](std::uint64_t v) { return v >= saturated ? std::string("more than 2^62") : std::to_string(v); };
    if (visits > limits_.max_node_instances)
      fail("the scene instances its nodes " + shown(visits) +
           " times (a node listed by several parents is instanced once per path), "
           "beyond the limit of " +
           std::to_string(limits_.max_node_instances));
    if (triangles > limits_.max_triangles)
      fail("the scene instances " + shown(triangles) + " triangles, beyond the limit of " + std::to_string(limits_.max_triangles));
  }

  // The scene's nodes, depth first without recursion (a chain of 20000 nodes is no stack depth).
  void traverse_scene(GltfAsset&) {
    const std::vector<int> roots = scene_roots();
    check_instance_counts(roots);
    struct Pending {
      int node;
      Mat4 parent;
    };
    std::vector<Pending> stack;
    for (auto root = roots.rbegin(); root != roots.rend(); ++root) stack.push_back({*root, Mat4{}});
    while (!stack.empty()) {
      const Pending pending = stack.back();
      stack.pop_back();
      const std::vector<int>& children = model_.nodes[static_cast<std::size_t>(pending.node)].children;
      const Mat4 world = visit(pending.node, pending.parent);
      for (auto child = children.rbegin(); child != children.rend(); ++child) stack.push_back({*child, world});
    }
  }

  // One node instance: its mesh's primitives, camera and light, under `parent`; returns its world matrix.
  Mat4 visit(int index, const Mat4& parent) {
    const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(index)];
    const Mat4 world = multiply(parent, local_matrix(node));
    if (node.mesh >= 0) {
      if (node.mesh >= static_cast<int>(model_.meshes.size()))
        fail("node " + std::to_string(index) + ": mesh " + std::to_string(node.mesh) + " does not exist");
      const tinygltf::Mesh& mesh = model_.meshes[static_cast<std::size_t>(node.mesh)];
      for (std::size_t p = 0; p < mesh.primitives.size(); ++p)
        add_primitive(mesh.primitives[p], world, "mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(p));
    }
    if (node.camera >= 0 && !camera_) take_camera(node, world);
    if (!light_) take_light(node, world);
    return world;
  }

  void take_camera(const tinygltf::Node& node, const Mat4& world) {
    if (node.camera >= static_cast<int>(model_.cameras.size())) fail("camera " + std::to_string(node.camera) + " does not exist");
    const tinygltf::Camera& c = model_.cameras[static_cast<std::size_t>(node.camera)];
    if (c.type != "perspective" || !(c.perspective.yfov > 0.0 && c.perspective.yfov < kPi)) return;
    Camera camera;
    camera.position = world.point({0.0, 0.0, 0.0});
    const Vec3 forward = world.vector({0.0, 0.0, -1.0}), up = world.vector({0.0, 1.0, 0.0});
    if (!is_bounded(camera.position) || !(length(forward) > 0.0) || !(length(cross(forward, up)) > 0.0) ||
        !std::isfinite(length(forward)) || !std::isfinite(length(up)))
      fail("camera " + std::to_string(node.camera) + ": its node transform leaves no view (position " + coordinates(camera.position) +
           ", forward " + coordinates(forward) + ", up " + coordinates(up) + ")");
    camera.look_at = camera.position + normalize(forward);
    camera.up = normalize(up);
    camera.fov_y_degrees = c.perspective.yfov * 180.0 / kPi;
    camera_ = camera;
  }

  void take_light(const tinygltf::Node& node, const Mat4& world) {
    auto it = node.extensions.find("KHR_lights_punctual");
    if (it == node.extensions.end()) return;
    const int index = index_member(it->second, "light", "node KHR_lights_punctual");
    if (index < 0 || index >= static_cast<int>(model_.lights.size()))
      fail("KHR_lights_punctual light " + std::to_string(index) + " does not exist");
    const tinygltf::Light& l = model_.lights[static_cast<std::size_t>(index)];
    Light light;
    if (l.type == "directional") {
      light.kind = Light::Kind::directional;
      const Vec3 towards = world.vector({0.0, 0.0, 1.0});  // towards the light: the node's +z
      if (!(length(towards) > 0.0) || !std::isfinite(length(towards)))
        fail("light " + std::to_string(index) + ": its node transform leaves no direction (" + coordinates(towards) + ")");
      light.vector = normalize(towards);
      light.intensity = 1.0;
    } else {
      light.kind = Light::Kind::point;
      light.vector = world.point({0.0, 0.0, 0.0});
      if (!is_bounded(light.vector))
        fail("light " + std::to_string(index) + ": its position " + coordinates(light.vector) + " is not finite");
    }
    light_ = light;
  }

  void add_primitive(const tinygltf::Primitive& primitive, const Mat4& world, const std::string& where) {
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      static const char* names[] = {"points", "lines", "line loop", "line strip"};
      fail(where + ": mode " + std::to_string(mode) + " (" + (mode >= 0 && mode < 4 ? names[mode] : "unknown") +
           "); only triangles can be rendered");
    }
    if (!primitive.attributes.count("POSITION")) fail(where + ": no POSITION attribute");
    const int material = primitive.material < 0 ? default_material_ : primitive.material;
    if (material > default_material_) fail(where + ": material " + std::to_string(primitive.material) + " does not exist");
    const bool has_normals = primitive.attributes.count("NORMAL") > 0;
    const bool has_uv = primitive.attributes.count("TEXCOORD_0") > 0;
    const bool has_tangents = primitive.attributes.count("TANGENT") > 0;
    std::vector<MeshVertex> local = read_vertices(primitive, material, where);
    const std::vector<std::uint32_t> index = indices(primitive, local.size(), where);
    std::vector<std::array<int, 3>> triangles = assemble(index, mode);
    if (triangles.empty()) return;
    if (triangles_.size() + triangles.size() > limits_.max_triangles)
      fail(std::to_string(triangles_.size() + triangles.size()) + " triangles so far, beyond the limit of " +
           std::to_string(limits_.max_triangles));
    if (!has_normals) unweld_with_face_normals(local, triangles);
    if (vertices_.size() + local.size() > limits_.max_vertices)
      fail(std::to_string(vertices_.size() + local.size()) + " vertices so far, beyond the limit of " +
           std::to_string(limits_.max_vertices));
    to_world(local, world, has_tangents, where);
    if (has_tangents) {
      for (MeshVertex& v : local) {
        const Vec3 t = v.tangent - dot(v.tangent, v.normal) * v.normal;
        v.tangent = length(t) > 0.0 ? normalize(t) : ref::normal_frame_tangent(v.normal);
      }
    } else if (has_uv) {
      generate_tangents(local, triangles);
      ++generated_tangents_;
    } else {
      for (MeshVertex& v : local) v.tangent = ref::normal_frame_tangent(v.normal);
    }
    const int base = static_cast<int>(vertices_.size());
    const int object = static_cast<int>(object_material_.size());
    object_material_.push_back(material);
    vertices_.insert(vertices_.end(), local.begin(), local.end());
    for (const auto& tri : triangles) {
      triangles_.push_back({tri[0] + base, tri[1] + base, tri[2] + base});
      triangle_objects_.push_back(object);
    }
  }

  // A primitive's vertices in its mesh's space: POSITION, and NORMAL, TEXCOORD_0 and TANGENT where
  // it has them, each with as many elements as positions.
  std::vector<MeshVertex> read_vertices(const tinygltf::Primitive& primitive, int material, const std::string& where) const {
    const View positions = attribute(primitive, "POSITION", where, 3, false);
    const std::size_t n = positions.count;
    if (vertices_.size() + n > limits_.max_vertices)
      fail(where + ": " + std::to_string(vertices_.size() + n) + " vertices so far, beyond the limit of " +
           std::to_string(limits_.max_vertices));
    const bool has_uv = primitive.attributes.count("TEXCOORD_0") > 0;
    if (!has_uv && material < default_material_ && has_textures_[static_cast<std::size_t>(material)])
      fail(where + ": material " + std::to_string(material) + " is textured but the primitive has no TEXCOORD_0");
    std::vector<MeshVertex> local(n);
    for (std::size_t i = 0; i < n; ++i)
      local[i].position = {component(positions, i, 0), component(positions, i, 1), component(positions, i, 2)};
    auto check_count = [&](const View& v, const char* name) {
      if (v.count != n) fail(where + " " + name + ": " + std::to_string(v.count) + " elements for " + std::to_string(n) + " positions");
    };
    if (primitive.attributes.count("NORMAL") > 0) {
      const View normals = attribute(primitive, "NORMAL", where, 3, false);
      check_count(normals, "NORMAL");
      for (std::size_t i = 0; i < n; ++i) local[i].normal = {component(normals, i, 0), component(normals, i, 1), component(normals, i, 2)};
    }
    if (has_uv) {
      const View uv = attribute(primitive, "TEXCOORD_0", where, 2, true);
      check_count(uv, "TEXCOORD_0");
      for (std::size_t i = 0; i < n; ++i) local[i].uv = checked_uv({component(uv, i, 0), component(uv, i, 1)}, i, where);
    }
    if (primitive.attributes.count("TANGENT") > 0) {
      const View tangents = attribute(primitive, "TANGENT", where, 4, false);
      check_count(tangents, "TANGENT");
      for (std::size_t i = 0; i < n; ++i) {
        local[i].tangent = {component(tangents, i, 0), component(tangents, i, 1), component(tangents, i, 2)};
        local[i].tangent_sign = component(tangents, i, 3) < 0.0 ? -1.0 : 1.0;
      }
    }
    return local;
  }

  // The renderer samples a texture at the integer texel floor(u size - 1/2) (repeat addressing):
  // |u| size must stay well inside a 32-bit int for every texture the asset may have, and a hit's
  // uv is a convex combination of its triangle's, so the bound on the vertices holds for every hit.
  Vec2 checked_uv(Vec2 uv, std::size_t i, const std::string& where) const {
    const double uv_limit = std::ldexp(1.0, 30) / std::max(limits_.max_texture_size, 1);
    if (std::fabs(uv.x) <= uv_limit && std::fabs(uv.y) <= uv_limit) return uv;
    std::ostringstream s;
    s.precision(6);
    s << where << ": vertex " << i << "'s TEXCOORD_0 (" << uv.x << ", " << uv.y << ") is not finite or beyond " << uv_limit
      << " in magnitude (2^30 over the " << limits_.max_texture_size
      << " texels per side a texture may have: the texel index must stay a 32-bit integer)";
    fail(s.str());
  }

  // The vertices through the node transforms: finite positions, unit normals, tangents as vectors.
  void to_world(std::vector<MeshVertex>& local, const Mat4& world, bool has_tangents, const std::string& where) const {
    for (std::size_t i = 0; i < local.size(); ++i) {
      MeshVertex& v = local[i];
      v.position = world.point(v.position);
      if (!is_bounded(v.position))
        fail(where + ": vertex " + std::to_string(i) + "'s position after the node transforms (" + coordinates(v.position) +
             ") is not finite or beyond " + coordinates_limit() + " in magnitude; every position must be a finite point");
      v.normal = world.normal(v.normal);
      const double l = length(v.normal);
      if (!(l > 0.0) || !std::isfinite(l)) fail(where + ": a zero or non-finite normal");
      v.normal = v.normal / l;
      if (has_tangents) v.tangent = world.vector(v.tangent);
    }
  }

  // Triangle lists from TRIANGLES, TRIANGLE_STRIP (every other triangle's first two vertices
  // swapped, keeping the winding) and TRIANGLE_FAN (glTF 2.0 Sec. 3.7.2.1).
  std::vector<std::array<int, 3>> assemble(const std::vector<std::uint32_t>& index, int mode) const {
    std::vector<std::array<int, 3>> out;
    auto at = [&](std::size_t i) { return static_cast<int>(index[i]); };
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      for (std::size_t i = 0; i + 2 < index.size(); i += 3) out.push_back({at(i), at(i + 1), at(i + 2)});
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (std::size_t i = 0; i + 2 < index.size(); ++i)
        out.push_back(i % 2 == 0 ? std::array<int, 3>{at(i), at(i + 1), at(i + 2)} : std::array<int, 3>{at(i + 1), at(i), at(i + 2)});
    } else {
      for (std::size_t i = 1; i + 1 < index.size(); ++i) out.push_back({at(0), at(i), at(i + 1)});
    }
    return out;
  }

  // Flat normals (glTF 2.0 Sec. 3.7.2.1: "When normals are not specified, client
  // implementations MUST calculate flat normals"): three vertices of its own per triangle.
  static void unweld_with_face_normals(std::vector<MeshVertex>& vertices, std::vector<std::array<int, 3>>& triangles) {
    std::vector<MeshVertex> out;
    out.reserve(3 * triangles.size());
    for (auto& tri : triangles) {
      const Vec3 p0 = vertices[static_cast<std::size_t>(tri[0])].position, p1 = vertices[static_cast<std::size_t>(tri[1])].position,
                 p2 = vertices[static_cast<std::size_t>(tri[2])].position;
      const Vec3 face = cross(p1 - p0, p2 - p0);
      const Vec3 normal = length(face) > 0.0 ? normalize(face) : Vec3{0.0, 0.0, 1.0};
      for (int& i : tri) {
        MeshVertex v = vertices[static_cast<std::size_t>(i)];
        v.normal = normal;
        i = static_cast<int>(out.size());
        out.push_back(v);
      }
    }
    vertices = std::move(out);
  }

  // An image's encoded bytes, kept until a material uses it.
  struct EncodedImage {
    const unsigned char* data = nullptr;
    std::size_t size = 0;
    std::vector<unsigned char> owned;  // empty when data points into a buffer of the model
  };

  std::string path_;
  GltfLimits limits_;
  std::string base_dir_;  // the asset's folder, as tinygltf joins URIs to it
  std::vector<std::string> files_;
  std::uintmax_t total_bytes_ = 0;
  std::string uri_refusal_;
  std::map<int, EncodedImage> encoded_;
  tinygltf::Model model_;
  std::string warnings_;
  int default_material_ = 0;
  std::vector<bool> has_textures_;
  std::map<std::string, std::shared_ptr<const ScalarMap>> scalar_cache_;
  std::map<std::string, std::shared_ptr<const NormalMap>> normal_cache_;
  std::vector<MeshVertex> vertices_;
  std::vector<std::array<int, 3>> triangles_;
  std::vector<int> triangle_objects_;
  std::vector<int> object_material_;
  int generated_tangents_ = 0;
  mutable std::size_t texels_ = 0;  // level-0 texels of the textures decoded so far
  std::optional<Camera> camera_;
  std::optional<Light> light_;
};

double corner_angle(Vec3 a, Vec3 b) {
  const double la = length(a), lb = length(b);
  if (!(la > 0.0) || !(lb > 0.0)) return 0.0;
  return std::acos(std::clamp(dot(a, b) / (la * lb), -1.0, 1.0));
}

// The registered glTF scenes' assets, by scene id.
struct AssetRegistry {
  std::mutex mutex;
  std::map<int, std::shared_ptr<const GltfAsset>> by_scene;
};
AssetRegistry& asset_registry() {
  static AssetRegistry registry;
  return registry;
}

}  // namespace

void generate_tangents(std::vector<MeshVertex>& vertices, const std::vector<std::array<int, 3>>& triangles) {
  std::vector<Vec3> tangent_sum(vertices.size()), bitangent_sum(vertices.size());
  for (const auto& tri : triangles) {
    const MeshVertex& v0 = vertices[static_cast<std::size_t>(tri[0])];
    const MeshVertex& v1 = vertices[static_cast<std::size_t>(tri[1])];
    const MeshVertex& v2 = vertices[static_cast<std::size_t>(tri[2])];
    const Vec3 e1 = v1.position - v0.position, e2 = v2.position - v0.position;
    const Vec2 d1 = v1.uv - v0.uv, d2 = v2.uv - v0.uv;
    const double det = d1.x * d2.y - d2.x * d1.y;
    if (det == 0.0 || !std::isfinite(det)) continue;
    // [e1 e2] = [dpdu dpdv] [d1 d2].
    const Vec3 dpdu = (d2.y * e1 - d1.y * e2) / det;
    const Vec3 dpdv = (d1.x * e2 - d2.x * e1) / det;
    const std::array<double, 3> angles{corner_angle(e1, e2), corner_angle(v2.position - v1.position, v0.position - v1.position),
                                       corner_angle(v0.position - v2.position, v1.position - v2.position)};
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = static_cast<std::size_t>(tri[static_cast<std::size_t>(k)]);
      const Vec3 n = vertices[i].normal;
      const Vec3 t = dpdu - dot(dpdu, n) * n;
      if (!(length(t) > 0.0)) continue;
      tangent_sum[i] = tangent_sum[i] + angles[static_cast<std::size_t>(k)] * normalize(t);
      bitangent_sum[i] = bitangent_sum[i] + angles[static_cast<std::size_t>(k)] * dpdv;
    }
  }
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    MeshVertex& v = vertices[i];
    const Vec3 t = tangent_sum[i] - dot(tangent_sum[i], v.normal) * v.normal;
    if (!(length(t) > 1e-300)) {
      v.tangent = ref::normal_frame_tangent(v.normal);
      v.tangent_sign = 1.0;
      continue;
    }
    v.tangent = normalize(t);
    // Image up is -v: the bitangent n x t of an unmirrored mapping points along -dp/dv.
    v.tangent_sign = dot(cross(v.normal, v.tangent), bitangent_sum[i]) > 0.0 ? -1.0 : 1.0;
  }
}

namespace {

// A perceptual roughness factor times a texture's range (the factor alone without one).
std::pair<double, double> scaled_range(double factor, const std::shared_ptr<const ScalarMap>& map) {
  if (!map || map->empty()) return {factor, factor};
  const auto [low, high] = map->value_range();
  return {factor * low, factor * high};
}

}  // namespace

std::pair<double, double> GltfMaterial::roughness_range() const { return scaled_range(roughness_factor, roughness_map); }
std::pair<double, double> GltfMaterial::clearcoat_roughness_range() const {
  return scaled_range(clearcoat_roughness_factor, clearcoat_roughness_map);
}

std::string GltfMaterial::describe() const { return printable(name) + ": " + describe_factors(); }

std::string GltfMaterial::describe_factors() const {
  std::ostringstream s;
  s.precision(4);
  s << "roughness " << roughness_factor << (roughness_map ? " x G texture" : "");
  if (normal_map) s << ", normal texture " << normal_map->width(0) << "x" << normal_map->height(0) << " scale " << normal_scale;
  if (clearcoat) {
    s << ", clearcoat " << clearcoat_factor << " roughness " << clearcoat_roughness_factor
      << (clearcoat_roughness_map ? " x G texture" : "");
    if (clearcoat_normal_map) s << " normal texture " << clearcoat_normal_map->width(0) << "x" << clearcoat_normal_map->height(0);
  }
  if (anisotropy)
    s << ", anisotropy " << anisotropy_strength << " rotation " << anisotropy_rotation << (anisotropy_texture ? " x texture" : "");
  return s.str();
}

bool GltfAsset::has_coat_normal_map() const {
  if (!coat_surfaces) return false;
  for (const SurfaceTextures& t : coat_surfaces->by_object)
    if (t.normal_map) return true;
  return false;
}

bool GltfAsset::has_normal_map() const {
  for (std::size_t object = 0; object < object_material.size(); ++object)
    if (materials[static_cast<std::size_t>(object_material[object])].normal_map) return true;
  return false;
}

std::string GltfAsset::summary() const {
  std::ostringstream s;
  s << name << " (" << printable(path) << "): " << mesh->triangles().size() << " triangles, " << mesh->vertices().size() << " vertices, "
    << primitives << " primitives (" << generated_tangent_primitives << " with generated tangents), " << materials.size() - 1
    << " materials; camera " << (camera ? "the asset's" : "framed from the bounds") << ", light "
    << (light ? (light->kind == Light::Kind::directional ? "the asset's directional" : "the asset's point") : "directional (default)")
    << (coat_surfaces ? "; its clearcoat lobe is the scene " + name + "-coat" : std::string()) << "\n";
  // The materials the primitives use, those alike once (with their count), in order.
  std::vector<std::pair<std::string, int>> lines;
  for (int m : object_material) {
    const std::string line = materials[static_cast<std::size_t>(m)].describe();
    auto found = std::find_if(lines.begin(), lines.end(), [&](const auto& l) { return l.first == line; });
    if (found == lines.end()) {
      lines.emplace_back(line, 1);
    } else {
      ++found->second;
    }
  }
  for (const auto& [line, count] : lines) s << "  " << count << " x " << line << "\n";
  return s.str();
}

GltfAsset load_gltf(const std::string& path, const GltfLimits& limits) {
  Loader loader(path, limits);
  try {
    return loader.load();
  } catch (const GltfError&) {
    throw;
  } catch (const std::exception& error) {  // e.g. a NormalMap or TriangleMesh precondition
    throw GltfError(path + ": " + one_line(error.what()));
  }
}

Camera frame_bounds(Vec3 lo, Vec3 hi) {
  const Vec3 centre = 0.5 * (lo + hi);
  Camera camera;
  camera.fov_y_degrees = 35.0;
  const double yaw = 30.0 * kPi / 180.0, pitch = 20.0 * kPi / 180.0;
  const Vec3 back{std::sin(yaw) * std::cos(pitch), std::sin(pitch), std::cos(yaw) * std::cos(pitch)};  // towards the camera
  const Vec3 right = normalize(cross(Vec3{0.0, 1.0, 0.0}, back));
  const Vec3 up = cross(back, right);
  // The nearest distance D from the centre at which every corner of the box lies inside the
  // square view: a corner at (x, y) across and z towards the camera needs
  // max(|x|, |y|) <= (D - z) tan(fov / 2).
  const double tan_half = std::tan(0.5 * camera.fov_y_degrees * kPi / 180.0);
  double distance = 1e-9;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p = Vec3{corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z} - centre;
    const double across = ref::max(std::fabs(dot(p, right)), std::fabs(dot(p, up)));
    distance = ref::max(distance, dot(p, back) + across / tan_half);
  }
  camera.position = centre + 1.05 * distance * back;  // 5 % margin
  camera.look_at = centre;
  camera.up = {0.0, 1.0, 0.0};
  return camera;
}

Scene make_gltf_coat_scene(const std::shared_ptr<const GltfAsset>& asset, double rotation_radians) {
  const Scene base = make_gltf_scene(asset, rotation_radians);
  Scene coat(asset->name + "-coat", asset->mesh, Rigid{}, base.camera(), base.light(), 0.5 * (asset->bounds_lo + asset->bounds_hi),
             rotation_radians);
  return coat.with_surface_materials(asset->coat_surfaces);
}

Scene make_gltf_scene(const std::shared_ptr<const GltfAsset>& asset, double rotation_radians) {
  const Vec3 centre = 0.5 * (asset->bounds_lo + asset->bounds_hi);
  Camera camera = asset->camera ? *asset->camera : frame_bounds(asset->bounds_lo, asset->bounds_hi);
  Light light;
  if (asset->light) {
    light = *asset->light;
  } else {
    // From the camera's upper left, as the torus knot's light: (-0.4, 0.6, 1) in its frame.
    const Vec3 forward = normalize(camera.look_at - camera.position);
    const Vec3 right = normalize(cross(forward, camera.up));
    const Vec3 up = cross(right, forward);
    light = {Light::Kind::directional, normalize(-0.4 * right + 0.6 * up - 1.0 * forward), 1.0};
  }
  Scene scene(asset->name, asset->mesh, Rigid{}, camera, light, centre, rotation_radians);
  return scene.with_surface_materials(asset->surfaces);
}

namespace {

SceneId register_asset_lobe(const std::shared_ptr<const GltfAsset>& asset, const std::string& path, bool coat) {
  RegisteredScene registered;
  registered.name = coat ? asset->name + "-coat" : asset->name;
  registered.has_normal_map = coat ? asset->has_coat_normal_map() : asset->has_normal_map();
  if (coat) {
    registered.make = [asset](double rotation) { return make_gltf_coat_scene(asset, rotation); };
  } else {
    registered.make = [asset](double rotation) { return make_gltf_scene(asset, rotation); };
  }
  SceneId id;
  try {
    id = register_scene(std::move(registered), asset->path + (coat ? "#coat" : ""));
  } catch (const std::invalid_argument& e) {
    throw GltfError(path + ": " + e.what());
  }
  AssetRegistry& registry = asset_registry();
  std::lock_guard lock(registry.mutex);
  registry.by_scene[static_cast<int>(id)] = asset;
  return id;
}

}  // namespace

std::vector<SceneId> register_gltf_scenes(const std::string& path, const GltfLimits& limits) {
  std::error_code error;
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(path, error);
  const std::string key = error ? path : canonical.string();
  std::shared_ptr<const GltfAsset> asset;
  if (const auto existing = scene_from_name(sanitized_stem(path))) {
    if (const auto registered = gltf_asset_of(*existing); registered && registered->path == key) asset = registered;
  }
  if (!asset) asset = std::make_shared<const GltfAsset>(load_gltf(key, limits));
  std::vector<SceneId> ids{register_asset_lobe(asset, path, false)};
  if (asset->coat_surfaces) ids.push_back(register_asset_lobe(asset, path, true));
  return ids;
}

SceneId register_gltf_scene(const std::string& path, const GltfLimits& limits) { return register_gltf_scenes(path, limits).front(); }

bool is_gltf_coat_scene(SceneId id) {
  const std::shared_ptr<const GltfAsset> asset = gltf_asset_of(id);
  return asset && asset->coat_surfaces && scene_name(id) == asset->name + "-coat";
}

std::shared_ptr<const GltfAsset> gltf_asset_of(SceneId id) {
  AssetRegistry& registry = asset_registry();
  std::lock_guard lock(registry.mutex);
  const auto it = registry.by_scene.find(static_cast<int>(id));
  return it == registry.by_scene.end() ? nullptr : it->second;
}

}  // namespace saagen::measure
