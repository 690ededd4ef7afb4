#pragma once
// Plots as motus draws them: figures described in C++ (axes, scales, lines), drawn all at
// once by one run of gnuplot (Debian's gnuplot-nox) into PNG and SVG files. gnuplot starts in
// a few tens of milliseconds, where matplotlib takes a second: a small `motus compare` is done,
// plots included, in well under half a second. The script and the data are left beside the
// pictures (FOLDER/figures.gp, figures.dat), so anyone can redraw or restyle them.
#include <cmath>
#include <string>
#include <vector>

namespace motus::plot {

// symlog: logarithmic beyond ±threshold and linear inside, for a quantity that changes sign
// (an energy error that goes up and down) or is exactly 0 at times.
enum class Scale { linear, log, symlog };

struct Series {
  std::string name;             // the legend's entry
  std::vector<double> x, y;     // points that are not finite (or ≤ 0 on a log axis) leave a gap
  std::string style = "lines";  // "lines", "linespoints" or "points"
  bool dashed = false;          // a dashed line (a peer beside motus's own, say)
  // gnuplot's dash pattern ("(40,20)": 40 units drawn, 20 left out), or "" for what `dashed` and
  // the colour's place give (line_style in figure.cpp). Lines that may lie on each other (engines
  // that agree) each get their own, so that those drawn first show through the gaps of those drawn
  // over them.
  std::string dash = "";
  double line_width = 1.8;
  int point_type = 7;           // gnuplot's point type for "linespoints" and "points" (7: a disc)
  // Its colour: the palette's entry (figure.cpp), so that one engine keeps its colour in every
  // figure whoever else ran (kEngineColour); −1: by its place among the series.
  int colour = -1;
  // A series with no points at all, for the legend only: why it has none ("not supported: …").
  std::string none_because = "";
};

// The engines' places in the palette, the same in compare's figures and bench precision's.
namespace kEngineColour {
constexpr int motus = 0, box2d = 1, bullet = 2;
constexpr int first_free = 3;  // (the places after them)
}  // namespace kEngineColour

// The colour of motus's integrator at `place` in its table (all_integrators(), in
// motus/integrate/integrator_catalog.hpp): the first at motus's own place, the others after Box2D's
// and Bullet's, so that a method keeps its colour in every figure (bench precision's diagrams and the
// stress test's plots gave rk4 purple in one and green in the other).
constexpr int integrator_colour(int place) { return place == 0 ? kEngineColour::motus : place - 1 + kEngineColour::first_free; }

struct Figure {
  std::string stem;  // the files: FOLDER/stem.png and FOLDER/stem.svg
  std::string title, x_label, y_label;
  Scale x_scale = Scale::linear, y_scale = Scale::linear;
  double symlog_threshold = 1e-16;  // where a symlog axis turns linear
  std::vector<Series> series;
  std::string note;  // a line under the title (what to look at), or ""
  // Where the legend goes (gnuplot's words: "top left", "outside right top"), or "" for below the
  // plot, in as many columns (up to four) as its longest entry lets fit across the picture, which
  // widens for an entry longer than it (one can be long: "bullet: not finite from t = 900 s (blew
  // up)"). Never inside by default: a box there hides the lines that pass under it.
  std::string key = "";
  double x_from = NAN;  // where a linear x axis starts (NaN: at the data's lowest x)
  // What a value that is not finite stands for, in the legend: "<gap_from> t = 50 s (<gap_means>)".
  std::string gap_from = "not finite from", gap_means = "blew up";
  int width = 900, height = 480;
  // Vertical marks across the plot, each a dashed grey line at x with its words beside it, if any (a
  // theory's limit, against which the lines are read).
  struct Mark {
    double x;
    std::string words;
  };
  std::vector<Mark> x_marks;
  // Where the y axis ends (NaN: where the data end): room above a level that stands for "off the
  // chart" (a run that blew up drawn at the blow-up factor sat on the frame, every method's line in it).
  double y_to = NAN;
};

// Draws every figure with one gnuplot run, started with its default settings (no ~/.gnuplot).
// Returns "" or one line for the user (no gnuplot on PATH, gnuplot could not be started, or it
// failed: FOLDER/figures.log says why). Throws std::runtime_error when the script or the data
// cannot be written.
std::string draw(const std::vector<Figure>& figures, const std::string& folder);

// The gnuplot program (an absolute path), or "" when there is none.
std::string gnuplot_program();

}  // namespace motus::plot
