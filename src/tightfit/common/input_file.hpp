#pragma once
/// Reading input files with bounded work, and a record of what was read.
///
/// Every input file (scene, mesh, joints, state, checkpoint) is read through
/// read_input_file: only a regular file is read (a directory, device, FIFO or socket is
/// refused at once, without blocking on it), and its size is checked before reading.
/// Each file read is recorded with a hash of its bytes, so that a run can tell later
/// whether it would read the same inputs (`optimize --resume`).
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

namespace tightfit {

/// The largest input file read: 1 GiB (a body scan of tens of millions of triangles).
inline constexpr std::uintmax_t kMaxInputBytes = std::uintmax_t{1} << 30;

/// The bytes of the regular file `path`. Throws InputError naming `path` when it does not
/// exist, is not a regular file (named: folder, device, FIFO, socket), is larger than
/// `max_bytes`, or cannot be read.
std::string read_input_file(const std::filesystem::path& path,
                            std::uintmax_t max_bytes = kMaxInputBytes);

/// A 64-bit FNV-1a hash of `bytes` as 16 hexadecimal digits (not cryptographic: it tells
/// files apart, it does not resist forgery).
std::string content_hash(const std::string& bytes);

/// How many reads read_input_file has recorded so far in this process.
std::uint64_t input_reads();

/// The files this process has read with read_input_file after the first `since` reads
/// (input_reads() at some moment): absolute path (links resolved) → content_hash of the
/// bytes last read.
std::map<std::string, std::string> input_files_read(std::uint64_t since = 0);

}  // namespace tightfit
