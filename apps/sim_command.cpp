#include "apps/sim_command.hpp"

#include <fmt/format.h>

#include <iostream>

#include "apps/cli_support.hpp"
#include "apps/sim_render_command.hpp"
#include "sim/world.hpp"

namespace neopipe::apps {
namespace {

Eigen::Vector2d parse_size_mm(const std::string& text, const std::string& option) {
  double w = 0;
  double h = 0;
  char x = 0;
  std::istringstream in(text);
  if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || !(in >> std::ws).eof() || !(w > 0 && h > 0)) {
    throw UsageError{option + " " + text + ": expected WxH in mm, e.g. 500x500"};
  }
  return {w, h};
}

int world_command(const SimWorldArgs& a) {
  sim::WorldRequest q;
  q.objects = a.objects;
  q.size = parse_size_mm(a.size, "--size");
  q.marble_diameter = a.diameter;
  q.min_gap = a.min_gap;
  q.seed = a.seed;
  const sim::World w = sim::generate_world(q);
  sim::save_world(w, a.out);
  std::cerr << fmt::format("neopipe sim world: {} marbles of {} mm in {} x {} mm (seed {}) -> {}\n", w.objects.size(),
                           w.marble_diameter, w.size.x(), w.size.y(), a.seed, a.out);
  return kExitOk;
}

}  // namespace

CLI::App* add_sim_command(CLI::App& parent, SimArgs& a) {
  CLI::App* sim =
      parent.add_subcommand("sim", "Simulator: make worlds, render camera frames and videos, drive the arm");
  sim->require_subcommand(1);

  CLI::App* world =
      sim->add_subcommand("world", "Scatter identical marbles at random, without overlap; write a world file");
  world->add_option("--objects", a.world.objects, "Number of marbles")->check(CLI::NonNegativeNumber);
  world->add_option("--size", a.world.size, "Workspace W x H in mm")->type_name("WxH")->capture_default_str();
  world->add_option("--diameter", a.world.diameter, "Marble diameter, mm")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  world->add_option("--min-gap", a.world.min_gap, "Smallest free space between two marbles, mm")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  world->add_option("--seed", a.world.seed, "Random seed: the same seed gives the same world")->capture_default_str();
  world->add_option("--out", a.world.out, "World file to write (YAML)")->required()->type_name("world.yaml");

  CLI::App* render = sim->add_subcommand("render", "Render one camera frame of a world (PNG), with the truth");
  add_sim_camera_options(*render, a.render.cam);
  render->add_option("--pose", a.render.pose, "Onboard camera pose x,y,theta (mm, mm, degrees; default: the centre)")
      ->type_name("X,Y,THETA");
  render->add_option("--out", a.render.cam.out, "Image to write")->required()->type_name("frame.png");
  render->add_option("--truth", a.render.cam.truth, "CSV id,u,v: where each visible marble's centre projects (px)")
      ->type_name("truth.csv");
  render
      ->add_option("--camera-out", a.render.camera_out,
                   "The camera's true intrinsics and pose (OpenCV FileStorage YAML), to check a calibration")
      ->type_name("camera.yml");
  render->add_option("--target", a.render.target, "Render a calibration target instead of the marbles")
      ->check(CLI::IsMember({"dots", "chessboard"}))
      ->type_name("dots|chessboard");
  render
      ->add_option("--target-grid", a.render.target_grid,
                   "Dots per row x rows, or a chessboard's inner corners (default 11x8 / 9x6)")
      ->type_name("CxR");
  render->add_option("--pitch", a.render.pitch, "Dot spacing or square side, mm")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  render->add_option("--dot-diameter", a.render.dot_diameter, "Dot diameter, mm")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  render
      ->add_option("--target-pose", a.render.target_pose,
                   "Target origin x,y,z (mm), turn theta, tilts about its axes (degrees; default 40,40,0,0,0,0)")
      ->type_name("X,Y,Z,THETA[,TX,TY]");
  render->footer(
      "With --target, --truth lists the dot centres or inner chessboard corners (id = row-major index).\n"
      "Pixel coordinates: (0,0) is the centre of the top-left pixel, as in OpenCV.");

  CLI::App* video = sim->add_subcommand(
      "video", "Render a video: the onboard camera along a path, or the global camera over moving marbles");
  add_sim_camera_options(*video, a.video.cam);
  video->add_option("--path", a.video.path, "Onboard: CSV with header x,y,theta (mm, mm, degrees), one pose per row")
      ->type_name("path.csv");
  video->add_option("--steps", a.video.steps, "Onboard: frames from one path pose to the next")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  video->add_option("--frames", a.video.frames, "Global: frames in the clip")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  video
      ->add_option("--speed", a.video.speed,
                   "Global: marble speed, mm/s (random headings; marbles bounce off the edges and each other)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  video->add_option("--fps", a.video.fps, "Frame rate")->check(CLI::Range(1.0, 1000.0))->capture_default_str();
  video->add_option("--out", a.video.cam.out, "Video to write (.mp4, .avi, .mkv)")->required()->type_name("clip.mp4");
  video->add_option("--truth", a.video.cam.truth, "CSV frame,id,u,v: projected marble centres per frame")
      ->type_name("truth.csv");
  video->add_flag("-q,--quiet", a.video.quiet, "No progress bar");

  CLI::App* arm =
      sim->add_subcommand("arm", "Drive the SCARA arm through tool-frame moves; report commanded vs actual poses");
  add_sim_arm_options(*arm, a.arm);
  return sim;
}

int sim_command(const CLI::App& sim, const SimArgs& a) {
  if (sim.got_subcommand("world")) return world_command(a.world);
  if (sim.got_subcommand("render")) return sim_render_command(a.render);
  if (sim.got_subcommand("video")) return sim_video_command(a.video);
  if (sim.got_subcommand("arm")) return sim_arm_command(a.arm);
  return kExitUsage;
}

}  // namespace neopipe::apps
