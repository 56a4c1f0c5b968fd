#pragma once
// A film made in segments by the ranks of an MPI job. Every film is encoded
// in segments of the description's animation.segment_frames frames, each by
// an encoder of its own (media::VideoSegment: a closed group of pictures
// from a key frame), and joined by stream copy; a lone process encodes them
// one after another from its one run. Under mpirun each segment is a work
// item: a rank runs the figure's scene again from step 0 (recomputing the
// state at the segment's first frame is cheaper than sending it: the
// models step far faster than frames are drawn and encoded), draws only that
// segment's frames and encodes them; rank 0 runs the scene for its figure
// and writes the segments it gathered. The same segments, the same film.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/render/output_files.hpp"
#include "media/video.hpp"
#include "scenes/scene.hpp"
#include "scenes/work_items.hpp"

namespace app {

// Whether this run makes figure `d`'s film from segments made as work
// items: an MPI job of more than one rank writing an MP4 of more than one
// segment (a PNG sequence is drawn by rank 0 itself).
bool films_in_segments(const Description& d, const scenes::Scene& scene, const OutputOptions& options);

class FilmSegments : public scenes::WorkItems {
public:
    FilmSegments(const Description& d, const scenes::Scene& scene, const OutputOptions& options);
    int item_count() const override;
    std::string item_name(int item) const override;  // "film frames 120 to 239"
    nlohmann::json run_item(int item) const override;
    void check_result(int item, const nlohmann::json& result) const override;
    double item_bytes() const override;
    std::string depends_on() const override;

private:
    const Description& d_;
    const scenes::Scene& scene_;
    const OutputOptions& options_;
    int frames_, per_segment_;
};

// A segment's result, decoded: its frames' steps and its packets.
struct FilmSegment {
    std::vector<int> steps;
    std::vector<media::VideoPacket> packets;
};
FilmSegment film_segment(const nlohmann::json& result);

// The video settings of d's film (what FrameSink's writer and every segment use).
media::VideoOptions film_video_options(const Description& d, const OutputOptions& options);

}  // namespace app
