// The transport reference's disk cache: one file per solved problem, named by a 64-bit key.
//
// The key (lantern::Hasher) covers everything a solve reads: the code version below, the
// transport settings, the output window, the whole wall grid, the wall height, the light
// softness and directional angle scale, and every light and shadow proxy of the scene.
// Bump transport_code_version whenever the solver's results change for the same inputs.
//
// File format (native byte order, like the key): the 8 bytes "LTRANSP1", the code version
// (u32), the key (u64), the window (resolution, width, height as i32; view as 4 f32), the
// stats (photons u64, batches i32, converged i32, relative error f64, seconds f64), then
// the fields as f32 in TransportResult order. Trust boundary: a file that is short, long,
// from another version or key, or holds non-finite values is rejected, never half-read.
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/transport/solver.hpp"

#include <cstdint>
#include <string>

namespace lantern::transport {

inline constexpr std::uint32_t transport_code_version = 1;

// Error (exit code 2) when the view has no GI window.
Result<std::uint64_t> cache_key(const scene::Scene& scene, const TransportSettings& settings);

// <dir>/<key as 16 hex digits>.ltr
std::string cache_path(const std::string& dir, std::uint64_t key);

// $LANTERN_TRANSPORT_CACHE if set, else $XDG_CACHE_HOME/lantern/transport, else
// $HOME/.cache/lantern/transport, else "" (no cache).
std::string default_cache_dir();

// Reads a cached result; an error names the file and what is wrong with it.
Result<TransportResult> read_cached(const std::string& path, std::uint64_t key);
// Writes atomically (write_file_atomic), creating the folder.
Result<void> write_cached(const std::string& path, std::uint64_t key,
                          const TransportResult& result);

} // namespace lantern::transport
