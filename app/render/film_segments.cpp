#include "app/render/film_segments.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "app/render/frame_canvas.hpp"
#include "render/text.hpp"
#include "scenes/work_codec.hpp"

namespace app {
namespace {

// What a run for one segment writes into: the film's frames in its range,
// encoded as one segment; no figure, no progress shown.
class SegmentOutput : public scenes::Output {
public:
    SegmentOutput(const Description& d, const OutputOptions& options, scenes::FrameRange range)
        : d_(d), options_(options), range_(range) {}

    std::unique_ptr<scenes::Film> film(int width, int height) override {
        return std::make_unique<SegmentFilm>(*this, width, height);
    }
    void figure(const scenes::FigureDrawing&, nlohmann::json) override {}
    scenes::Progress& progress() override { return quiet_; }
    std::vector<nlohmann::json> results(const scenes::WorkItems&) override {
        throw std::logic_error(d_.id + ": a scene with work items has no film segments");
    }
    scenes::FrameRange film_frames() const override { return range_; }
    bool wants_figure() const override { return false; }

    nlohmann::json result() {
        nlohmann::json packets = nlohmann::json::array();
        for (const media::VideoPacket& p : packets_)
            packets.push_back({scenes::binary_of<std::uint8_t>(p.data), p.pts, p.dts, p.key});
        return {{"steps", steps_}, {"packets", packets}};
    }

private:
    struct SegmentFilm : scenes::Film {
        SegmentFilm(SegmentOutput& out, int width, int height)
            : out_(out),
              video_(out.d_.id + " film segment", width, height, film_video_options(out.d_, out.options_)),
              canvas_(width, height, [this](render::Image frame, int step) {
                  video_.add(frame);
                  out_.steps_.push_back(step);
              }) {}
        void add(const scenes::FrameDrawing& frame, int step) override { canvas_.draw(frame, step); }
        void flush() override { canvas_.flush(); }
        nlohmann::json finish() override {
            canvas_.flush();
            out_.packets_ = video_.finish();
            return {};
        }
        SegmentOutput& out_;
        media::VideoSegment video_;
        FrameCanvas canvas_;  // last: it hands its frames to video_
    };

    const Description& d_;
    const OutputOptions& options_;
    scenes::FrameRange range_;
    scenes::Progress quiet_;
    std::vector<int> steps_;
    std::vector<media::VideoPacket> packets_;
};

}  // namespace

media::VideoOptions film_video_options(const Description& d, const OutputOptions& options) {
    media::VideoOptions v = options.video_options;
    v.fps = d.animation->fps;
    v.segment_frames = d.animation->segment_frames;
    return v;
}

bool films_in_segments(const Description& d, const scenes::Scene& scene, const OutputOptions& options) {
    return options.work.cluster && options.work.cluster->size() > 1 && !scene.work() && d.animation && options.encodes() &&
           !options.frames && d.animation->segment_frames > 0 &&
           d.animation->frame_count() > d.animation->segment_frames;
}

FilmSegments::FilmSegments(const Description& d, const scenes::Scene& scene, const OutputOptions& options)
    : d_(d),
      scene_(scene),
      options_(options),
      frames_(d.animation->frame_count()),
      per_segment_(d.animation->segment_frames) {}

int FilmSegments::item_count() const {
    return (frames_ + per_segment_ - 1) / per_segment_;
}

std::string FilmSegments::item_name(int item) const {
    return "film frames " + std::to_string(item * per_segment_) + " to " +
           std::to_string(std::min(frames_, (item + 1) * per_segment_) - 1);
}

nlohmann::json FilmSegments::run_item(int item) const {
    render::clear_font_cache();  // the same pixels as a lone run, whatever this process drew before
    SegmentOutput out(d_, options_, {item * per_segment_, std::min(frames_, (item + 1) * per_segment_)});
    scene_.render(out);
    return out.result();
}

// The segment's steps, increasing within the film's window, and at most a
// packet a frame, each with a frame of the segment and dts increasing
// behind pts (what the muxer takes).
void FilmSegments::check_result(int item, const nlohmann::json& r) const {
    namespace rc = scenes::result_check;
    const int frames = std::min(frames_, (item + 1) * per_segment_) - item * per_segment_;
    const description::Animation& a = *d_.animation;
    long long previous = -1;
    for (const nlohmann::json& step : rc::array_of(rc::member(r, "steps"), "steps", frames)) {
        const long long s = rc::integer_in(step, "steps", a.first, a.last);
        if (s <= previous) throw std::invalid_argument("steps do not increase");
        previous = s;
    }
    const nlohmann::json& packets = rc::array_of(rc::member(r, "packets"), "packets", -1);
    if (packets.size() > static_cast<std::size_t>(frames))
        throw std::invalid_argument("packets holds " + std::to_string(packets.size()) + " packets for " +
                                    std::to_string(frames) + " frames");
    long long last_dts = -frames - 1;
    for (const nlohmann::json& p : packets) {
        rc::array_of(p, "a packet", 4);
        if (!p[0].is_binary()) throw std::invalid_argument("a packet holds no bytes");
        const long long pts = rc::integer_in(p[1], "a packet's pts", 0, frames - 1);
        const long long dts = rc::integer_in(p[2], "a packet's dts", -frames, pts);
        if (dts <= last_dts) throw std::invalid_argument("the packets' dts do not increase");
        last_dts = dts;
        rc::boolean(p[3], "a packet's key flag");
    }
}

// The film's bytes as require_disk bounds them (0.15 a pixel and frame), a
// segment's share, and a packet's overhead a frame.
double FilmSegments::item_bytes() const {
    const double pixels = double(scenes::scaled_even(d_.animation->width, options_.scale)) *
                          scenes::scaled_even(d_.animation->height, options_.scale);
    return per_segment_ * (0.15 * pixels + 64) + 1024;
}

// Beyond the scene, seed and [params]: everything that shapes the frames
// and their encoding.
std::string FilmSegments::depends_on() const {
    const description::Animation& a = *d_.animation;
    const media::VideoOptions v = film_video_options(d_, options_);
    std::ostringstream text;
    text << toml::json_formatter{d_.style} << "\npanels";
    for (int p : d_.panels) text << ' ' << p;
    text << "\nfigure " << d_.width << 'x' << d_.height << ' ' << d_.panel_title << "\nanimation " << a.first << ' '
         << a.last << ' ' << a.stride << ' ' << a.fps << ' ' << a.width << 'x' << a.height << ' ' << a.title << ' '
         << a.segment_frames << "\nscale " << options_.scale << "\nvideo " << v.codec << ' ' << v.crf << ' ' << v.preset
         << ' ' << v.tune << ' ' << v.threads;
    if (a.turn_frames > 0) text << "\nturn " << a.turn_frames;
    return text.str();
}

FilmSegment film_segment(const nlohmann::json& result) {
    FilmSegment s;
    s.steps = result.at("steps").get<std::vector<int>>();
    for (const nlohmann::json& p : result.at("packets")) {
        const nlohmann::json& data = p.at(0);
        s.packets.push_back({scenes::values_of<std::uint8_t>(data, data.is_binary() ? data.get_binary().size() : 0),
                             p.at(1).get<std::int64_t>(), p.at(2).get<std::int64_t>(), p.at(3).get<bool>()});
    }
    return s;
}

}  // namespace app
