#include "motus/plot/figure.hpp"
#include "motus/plot/write_failure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cctype>
#include <fstream>
#include <iterator>
#include <utility>
#include <sstream>
#include <stdexcept>

#include "motus/process/run_program.hpp"

namespace motus::plot {
namespace {

// A string as gnuplot's single-quoted literal (only the quote itself is special there).
std::string quoted(const std::string& text) {
  std::string q = "'";
  for (char c : text) {
    if (c == '\'') q += "''";
    else if (c == '\n' || c == '\r') q += ' ';
    else q += c;
  }
  return q + "'";
}

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", x);
  return text;
}

// The colours of motus's engines and lines: the renders' eight body colours first, then a
// darker eight, so that a figure of up to sixteen lines (a work-precision diagram's methods
// and peers) gives each its own colour. Each has a contrast of at least 3:1 against the white
// background (WCAG 1.4.11, graphical objects): the renders' orange, green, teal and yellow did not
// (2.96, 2.92, 2.80 and 1.98) and are darkened here, keeping their hue, to 3.1 or more.
const char* const kColours[] = {"#4285d6", "#df7430", "#43a360", "#cd465a", "#9164c8", "#26a0a9", "#ae8e20", "#966e50",
                                "#1f3f7a", "#a04010", "#2a6e3c", "#8b1e2e", "#5a3a8a", "#1a6e75", "#8a7010", "#4a3428"};

// Line k's colour and dash: the series' own dash when it has one (compare's engines); else lines
// 17 to 32 take the colours again, dotted (gnuplot's dash type 3) or, when the series is dashed on
// purpose (a peer beside motus's own), dash-dotted (4). So no two of a figure's first 32 lines
// look the same (no figure motus draws has more). Of the first 16, the first is solid and the
// others not dashed on purpose take one of four patterns in turn: a line drawn over another
// that follows the same curve (symplectic Euler's two forms on a stress page) leaves it showing
// through its gaps, where two solid lines showed only the last one drawn.
const char* const kLineDashes[] = {"(12,6)", "(3,5)", "(12,4,3,4)", "(24,6,3,6)"};
std::string line_style(size_t k, bool dashed, const std::string& dash) {
  const std::string colour = std::string(" lc rgb '") + kColours[k % std::size(kColours)] + "'";
  if (!dash.empty()) return colour + " dt " + dash;
  if ((k / std::size(kColours)) % 2 == 1) return colour + (dashed ? " dt 4" : " dt 3");
  if (dashed) return colour + " dt 2";
  return k == 0 ? colour : colour + " dt " + kLineDashes[(k - 1) % std::size(kLineDashes)];
}

void axis(std::ostream& gp, const char* name, Scale scale, double threshold) {
  gp << "unset logscale " << name << "\nunset nonlinear " << name << "\n";
  if (scale == Scale::log) gp << "set logscale " << name << " 10\nset format " << name << " '%.0e'\n";
  if (scale == Scale::symlog) {
    const std::string t = number(threshold);
    gp << "set nonlinear " << name << " via sgn(" << name << ")*log10(1+abs(" << name << ")/" << t
       << ") inverse sgn(" << name << ")*" << t << "*(10**abs(" << name << ")-1)\n"
       << "set format " << name << " '%.0e'\n";
  }
  if (scale == Scale::linear) gp << "set format " << name << " '%g'\n";
}

// The note under the title, in lines that fit across the picture (its 9-point font: about 6.75 px a
// character, 9/10 of the legend's 7.5): one long line was cut off at both edges. Broken after "; "
// where it can be (the note's clauses), else at a space; at most kMostNoteLines lines.
constexpr int kNoteLabel = 10, kMostNoteLines = 4;  // (labels 10 to 13; 1 to 3 are the figure's others)
constexpr int kMarkLabel = 20, kMostMarks = 8;     // (the x marks' labels and arrows: 20 to 27)
constexpr double kNoteLinePixels = 13;
std::vector<std::string> wrap_note(const std::string& note, int width) {
  std::vector<std::string> lines;
  const size_t fits = static_cast<size_t>(std::max(40.0, (width - 40) / 6.75));
  std::string rest = note;
  while (!rest.empty() && static_cast<int>(lines.size()) < kMostNoteLines - 1 && rest.size() > fits) {
    size_t cut = rest.rfind("; ", fits);
    size_t skip = 2;
    if (cut == std::string::npos || cut < fits / 2) cut = rest.rfind(' ', fits), skip = 1;
    if (cut == std::string::npos || cut == 0) break;
    lines.push_back(rest.substr(0, cut + (skip == 2 ? 1 : 0)));  // (the ";" stays at the line's end)
    rest = rest.substr(cut + skip);
  }
  if (!rest.empty()) lines.push_back(rest);
  return lines;
}

// About how tall the plot's axes are in the picture: the height less the margins, in lines of
// about 14 px (the title and the note's lines above; the tics, the x label and a legend's rows below).
constexpr double kLinePixels = 14;
double plot_pixels(const Figure& f, int legend_rows, size_t note_line_count) {
  return std::max(100.0, f.height - kLinePixels * (3 + static_cast<double>(note_line_count) + 4 + legend_rows));
}

// A tic label's height and a little: tics closer than this print their labels over each other.
constexpr double kTicLabelPixels = 14;

bool plottable(double v, Scale scale) { return std::isfinite(v) && (scale != Scale::log || v > 0); }

// Where on the x axis, in the axis's own words: "t = 1500 s" (its label "t [s]"), "h = 0.1 s" ("h [s]"),
// "radii per step = 1000" ("radii per step"); "x = 1500" for an axis with no label. (It said
// "x = 1000" on an axis of radii per step.)
std::string at_x(const Figure& f, double x) {
  const std::string& label = f.x_label;
  const size_t open = label.find(" ["), close = label.find(']', open);
  if (open != std::string::npos && close != std::string::npos)
    return label.substr(0, open) + " = " + number(x) + " " + label.substr(open + 2, close - open - 2);
  const size_t remark = label.rfind(" (");  // (without a remark in brackets at its end)
  const std::string name = !label.empty() && label.back() == ')' && remark != std::string::npos ? label.substr(0, remark) : label;
  return (name.empty() ? "x" : name) + " = " + number(x);
}

// What a series' legend entry adds to its name: why it has no line, where it stops being finite
// (a run that blew up: its line ends there, and a figure looked at alone must say why), and the
// exact zeros a log axis cannot show (its line has gaps there).
std::string legend_tail(const Figure& f, const Series& s) {
  if (!s.none_because.empty()) return ": " + s.none_because;
  long finite = 0, zeros = 0, total = 0;
  double first_not_finite = NAN;
  for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
    ++total;
    if (!std::isfinite(s.y[i])) {
      if (std::isnan(first_not_finite)) first_not_finite = s.x[i];
      continue;
    }
    ++finite;
    zeros += s.y[i] == 0;
  }
  std::string tail;
  const bool blew_up = !std::isnan(first_not_finite);
  if (blew_up) tail = f.gap_from + " " + at_x(f, first_not_finite) + " (" + f.gap_means + ")";
  if (f.y_scale == Scale::log && zeros > 0) {
    const std::string exact = zeros == finite ? (blew_up ? "exactly 0 until then" : "exactly 0 throughout")
                                              : "exactly 0 at " + std::to_string(zeros) + " of " +
                                                    std::to_string(total) + " points (the gaps)";
    tail = tail.empty() ? exact : tail + "; " + exact;
  }
  if (tail.empty() && finite == 0) tail = "no finite point";
  return tail.empty() ? "" : ": " + tail;
}

// A symlog axis's range and tics: out to the next whole decade beyond the data on each side (so
// that no line runs along the frame and the end tics are labelled), 0, and the decades from the
// threshold up, every one of them or every second, third, ... so that each side has at most five.
// `axis_pixels`: about how tall the axis is in the picture, for the tics' spacing.
void symlog_range(std::ostream& gp, const char* name, double low, double high, double threshold, double axis_pixels) {
  auto decade_above = [&](double v) { return std::max(threshold, std::pow(10.0, std::ceil(std::log10(v) - 1e-9))); };
  const double top = high > 0 ? decade_above(high) : 0, bottom = low < 0 ? -decade_above(-low) : 0;
  const double range_low = bottom == 0 && top == 0 ? -threshold : bottom, range_high = top == 0 && bottom == 0 ? threshold : top;
  gp << "set " << name << "range [" << number(range_low) << ":" << number(range_high) << "]\n";
  // (On the axis's own scale, as the nonlinear mapping above: sgn(y)·log10(1 + |y|/threshold).)
  const auto mapped = [&](double y) { return std::copysign(std::log10(1 + std::abs(y) / threshold), y); };
  const double pixels_per_unit = axis_pixels / (mapped(range_high) - mapped(range_low));
  const int lowest = static_cast<int>(std::lround(std::log10(threshold)));
  std::string tics = "'0' 0";
  for (const bool above : {true, false}) {
    const double end = above ? top : -bottom;
    if (end <= 0) continue;
    const int highest = static_cast<int>(std::lround(std::log10(end)));
    const int stride = std::max(1, (highest - lowest + 5) / 5);
    for (int k = highest; k >= lowest; k -= stride) {
      // A tic closer to 0 than a label's height would print its label over 0's (±threshold is only
      // log10(2) of a decade from 0): 0 is the one to keep, where the runs start.
      if (k != highest && mapped(std::pow(10.0, k)) * pixels_per_unit < kTicLabelPixels) continue;
      char label[32];
      std::snprintf(label, sizeof label, "%.0e", std::pow(10.0, k));
      const std::string sign = above ? "" : "-";
      tics += ", '" + sign + label + "' " + sign + number(std::pow(10.0, k));
    }
  }
  gp << "set " << name << "tics (" << tics << ")\n";
}

}  // namespace

std::string gnuplot_program() { return process::find_program("gnuplot"); }

std::string draw(const std::vector<Figure>& figures, const std::string& folder) {
  if (figures.empty()) return "";
  // The data: one block per series, blocks separated by two blank lines (gnuplot's "index").
  const std::string data_file = folder + "/figures.dat";
  std::ofstream data(data_file);
  std::ostringstream gp;
  gp << "# Written by motus: every figure of this folder. Redraw with `gnuplot -d figures.gp` (-d: without your ~/.gnuplot).\n"
     << "set encoding utf8\nset grid lc rgb '#dddddd'\nset key top left Left reverse box opaque\n"
     << "set border lc rgb '#555555'\nset tics nomirror\n";
  int block = 0;
  for (const auto& f : figures) {
    // Each series' plottable points as a block of the data file; a series with none (exactly 0
    // throughout, on a log axis) is still named in the legend, so that it is seen to be exact.
    std::vector<int> blocks;
    double x_low = INFINITY, x_high = -INFINITY, y_low = INFINITY, y_high = -INFINITY;
    long points = 0;
    bool not_finite = false;  // some value (not all: then points > 0) is not finite
    for (const auto& s : f.series) {
      long mine = 0;
      for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
        if (std::isfinite(s.x[i])) x_low = std::min(x_low, s.x[i]), x_high = std::max(x_high, s.x[i]);
        not_finite = not_finite || !std::isfinite(s.y[i]);
        if (plottable(s.x[i], f.x_scale) && plottable(s.y[i], f.y_scale)) {
          ++mine;
          y_low = std::min(y_low, s.y[i]), y_high = std::max(y_high, s.y[i]);
        }
      }
      if (mine == 0) {
        blocks.push_back(-1);
        continue;
      }
      points += mine;
      data << "# " << f.stem << ": " << s.name << "\n";
      bool gap = false;
      for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
        if (plottable(s.x[i], f.x_scale) && plottable(s.y[i], f.y_scale)) {
          data << number(s.x[i]) << ' ' << number(s.y[i]) << '\n';
          gap = false;
        } else if (!gap) {
          data << '\n';  // a gap in the line
          gap = true;
        }
      }
      data << "\n\n";
      blocks.push_back(block++);
    }
    std::string plot_line;
    for (size_t k = 0; k < f.series.size(); ++k) {
      const auto& s = f.series[k];
      const std::string colour = line_style(s.colour >= 0 ? static_cast<size_t>(s.colour) : k, s.dashed, s.dash);
      if (blocks[k] < 0) {
        plot_line += k ? ", " : "plot ";
        // (One with nothing to draw, for a reason, has no sample line: "box2d: not supported" beside an
        // orange dash read as a line that was somewhere in the plot.)
        plot_line += std::string("1/0 with lines ") +
                     (s.none_because.empty() ? "lw " + number(s.line_width) + colour : std::string("lt nodraw")) + " title " +
                     quoted(s.name + legend_tail(f, s));
        continue;
      }
      const std::string pt = std::to_string(s.point_type);
      plot_line += (k ? ", " : "plot ") + quoted("figures.dat") + " index " + std::to_string(blocks[k]) + " using 1:2 with " +
                   (s.style == "points"        ? "points pt " + pt + " ps 0.8"
                    : s.style == "linespoints" ? "linespoints pt " + pt + " ps 0.6 lw 1.5"
                                               : "lines lw " + number(s.line_width)) +
                   colour + " title " + quoted(s.name + legend_tail(f, s));
    }
    // The legend below the plot, in as many columns as its longest entry lets fit across the
    // picture (about 7.5 px a character of the 10-point font, and the sample line; at 6 px two
    // columns were counted where gnuplot drew one, its third row over the x axis's label): the
    // plot keeps the picture's width whatever the entries say.
    const bool below = f.key.empty();
    size_t longest = 0;
    for (const auto& s : f.series) longest = std::max(longest, s.name.size() + legend_tail(f, s).size());
    // A legend entry wider than the picture (a line that failed says where and why) widens it: one
    // was cut off at the picture's right edge.
    const int width = below ? std::max(f.width, 15 * static_cast<int>(longest) / 2 + 190) : f.width;
    const std::vector<std::string> note_lines = wrap_note(f.note, width);
    const int columns = std::clamp((width - 80) / (15 * static_cast<int>(longest) / 2 + 70), 1, 4);
    const int rows = (static_cast<int>(f.series.size()) + columns - 1) / columns;
    const std::string key = !below ? f.key + " Left reverse box opaque"
                                   : "below Left reverse box maxrows " + std::to_string(std::max(rows, 1));
    gp << "set autoscale\nset xtics autofreq\nset ytics autofreq\nunset label 2\nset key " << key << "\n";
    // (Every mark of the figure before is taken away; this figure's are drawn behind its lines.)
    gp << "unset arrow\n";
    for (int k = kMarkLabel; k < kMarkLabel + kMostMarks; ++k) gp << "unset label " << k << "\n";
    for (size_t k = 0; k < f.x_marks.size() && k < static_cast<size_t>(kMostMarks); ++k) {
      const int id = kMarkLabel + static_cast<int>(k);
      const std::string x = number(f.x_marks[k].x);
      gp << "set arrow " << id << " from " << x << ", graph 0 to " << x << ", graph 1 nohead back dt 2 lw 1 lc rgb '#888888'\n";
      if (!f.x_marks[k].words.empty())
        gp << "set label " << id << " " << quoted(f.x_marks[k].words) << " at " << x
           << ", graph 0.98 rotate by 90 right offset -0.9,0 font ',9' tc rgb '#555555'\n";
    }
    if (!std::isnan(f.y_to) && points > 0 && f.y_scale != Scale::symlog) gp << "set yrange [:" << number(f.y_to) << "]\n";
    // The whole run on the x axis, also where a line has gaps (exact values on a log axis).
    if (!std::isnan(f.x_from) && f.x_scale == Scale::linear) x_low = std::min(x_low, f.x_from);
    if (x_high > x_low && f.x_scale == Scale::linear)
      gp << "set xrange [" << number(x_low) << ":" << number(x_high) << "]\n";
    if (points == 0) {  // nothing to draw: give the axes a range, and say why it is empty
      // (Values that are all 0 on a log axis, or no values at all: every series is an engine
      // that could not run the scene.)
      const bool values = std::any_of(f.series.begin(), f.series.end(), [](const Series& s) { return !s.x.empty(); });
      if (!(x_high > x_low)) gp << "set xrange [0:1]\n";
      gp << "set yrange " << (f.y_scale == Scale::log ? "[1e-17:1e-13]" : "[-1:1]") << "\n"
         << "set label 2 '"
         << (!values      ? "nothing to draw: no run has data for this figure"
             : not_finite ? "nothing finite to draw: the runs blew up (see the legend)"
                          : "every value is exactly 0")
         << "' at graph 0.5, graph 0.5 center tc rgb '#555555'\n";
    }
    if (plot_line.empty()) {
      // No series at all (no engine or method could run the scene): the figure is still drawn, as
      // empty axes that say so, since every page links its figures.
      axis(gp, "x", Scale::linear, 0);
      axis(gp, "y", Scale::linear, 0);
      gp << "set xrange [0:1]\nset yrange [0:1]\n"
         << "set label 2 'nothing to draw: no run has data for this figure' at graph 0.5, graph 0.5 center tc rgb '#555555'\n";
      plot_line = "plot 2 notitle";  // (a line outside the range: the axes alone)
    } else {
      axis(gp, "x", f.x_scale, f.symlog_threshold);
      axis(gp, "y", f.y_scale, f.symlog_threshold);
      if (f.y_scale == Scale::symlog && points > 0)
        symlog_range(gp, "y", y_low, y_high, f.symlog_threshold, plot_pixels(f, below ? rows : 0, note_lines.size()));
    }
    // Plain text throughout (no "enhanced" markup: a scene called ball_gas keeps its underscore).
    // The title and the note under it (the legend may be below the plot) are labels centred on the
    // picture, not on the plot (gnuplot's title is, and a legend at the right pushed a long note
    // off the picture's left edge); the top margin keeps their lines. The bottom margin holds the
    // tics, the x label and, below them, the legend's rows.
    const auto from_top = [&](double pixels) { return number(1 - pixels / f.height); };
    gp << "unset title\nset label 3 " << quoted(f.title) << " at screen 0.5, screen " << from_top(16) << " center\n";
    for (int line = 0; line < kMostNoteLines; ++line) gp << "unset label " << kNoteLabel + line << "\n";
    for (size_t line = 0; line < note_lines.size(); ++line)
      gp << "set label " << kNoteLabel + static_cast<int>(line) << " " << quoted(note_lines[line]) << " at screen 0.5, screen "
         << from_top(32 + kNoteLinePixels * static_cast<double>(line)) << " center font ',9' tc rgb '#555555'\n";
    gp << "set tmargin " << 3 + note_lines.size() << "\nset xlabel " << quoted(f.x_label) << "\nset ylabel "
       << quoted(f.y_label) << "\nset bmargin " << (below ? 4 + rows : 4) << "\n";
    for (const char* format : {"png", "svg"}) {
      if (std::string(format) == "png")
        gp << "set terminal pngcairo size " << width << "," << f.height << " font 'DejaVu Sans,10' noenhanced\n";
      else
        gp << "set terminal svg size " << width << "," << f.height << " font 'DejaVu Sans,10' noenhanced background '#ffffff'\n";
      gp << "set output " << quoted(f.stem + "." + format) << "\n" << plot_line << "\n";
    }
  }
  data.flush();
  if (!data) throw std::runtime_error(write_failure(data_file));
  const std::string script_file = folder + "/figures.gp";
  {
    errno = 0;
    std::ofstream script(script_file);
    script << gp.str() << "set output\n";
    script.flush();
    if (!script) throw std::runtime_error(write_failure(script_file));
  }
  const std::string gnuplot = gnuplot_program();
  if (gnuplot.empty()) return "plots skipped: gnuplot not found on PATH (apt-get install gnuplot-nox)";
  // -d (--default-settings): neither the user's ~/.gnuplot nor the system's gnuplotrc is read
  // first. A user's `set decimalsign ","` there made every tick label "0,5"; the script sets
  // everything else it depends on itself.
  const process::Outcome run = process::run_program({gnuplot, "-d", "figures.gp"}, folder, folder + "/figures.log");
  // (Named within the report: `folder` is often a partial one, renamed once the report is whole.)
  // Ended by an interrupt (process::stop_running_programs): the run stops here, and its caller's
  // partial folder goes with it (not a report whose plots "failed").
  if (!run.ok() && process::stopping()) throw std::runtime_error("interrupted while gnuplot drew the plots");
  if (!run.ok()) {
    // What gnuplot had drawn when it failed is no picture to show: every figure's files go, and
    // the page and the terminal say the plots failed.
    for (const auto& f : figures)
      for (const char* format : {".png", ".svg"}) std::remove((folder + "/" + f.stem + format).c_str());
    // (Never started, it wrote nothing in figures.log: the reason is motus's to give.)
    if (!run.started)
      return "plots failed: " + run.not_started("gnuplot", gnuplot);
    return "plots failed: gnuplot's messages are in the report's figures.log";
  }
  // gnuplot says nothing when a picture's write fails (a full disk, a file-size limit): it exits 0
  // and leaves it cut short. A picture that does not end as its format does is a failed write.
  for (const auto& f : figures)
    for (const auto& [format, ending] : {std::pair{".png", std::string("IEND\xae\x42\x60\x82", 8)},
                                         std::pair{".svg", std::string("</svg>")}}) {
      const std::string name = f.stem + format;
      std::ifstream picture(folder + "/" + name, std::ios::binary);
      std::string bytes((std::istreambuf_iterator<char>(picture)), std::istreambuf_iterator<char>());
      while (!bytes.empty() && std::isspace(static_cast<unsigned char>(bytes.back()))) bytes.pop_back();
      if (bytes.size() < ending.size() || bytes.compare(bytes.size() - ending.size(), ending.size(), ending) != 0)
        throw std::runtime_error(folder + "/" + name + ": could not be written whole (gnuplot's picture ends short: a "
                                 "full disk or a file-size limit)");
    }
  return "";
}

}  // namespace motus::plot
