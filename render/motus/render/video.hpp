#pragma once
// Frames to a video file with the ffmpeg program (Debian's ffmpeg package): MP4
// (H.264, yuv420p, even dimensions) or an animated GIF with its own palette.
#include <optional>
#include <string>

namespace motus::render {

enum class VideoFormat { mp4, gif };

// "mp4" / "gif" → the format; nullopt for anything else.
std::optional<VideoFormat> video_format_from_name(const std::string& name);

// Runs ffmpeg on frames named by a printf pattern ("out/frame_%05d.png", numbered from 0)
// at `fps` frames per second into out_path (replaced if it exists). Only the file name is a
// pattern: a % in the folder's name ("runs/c_50%/frame_%05d.png") is taken as it is.
// Throws RenderError when ffmpeg is not on $PATH (install the Debian package ffmpeg), and
// std::runtime_error when ffmpeg runs and fails.
void encode_video(const std::string& frame_pattern, double fps, const std::string& out_path, VideoFormat format);

}  // namespace motus::render
