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

void add_sim_camera_options(CLI::App& cmd, SimCameraArgs& a) {
  cmd.add_option("--world", a.world, "World file (YAML), e.g. from neopipe sim world")->required()->type_name("W.yaml");
  cmd.add_option("--camera", a.camera, "Which camera: global (above the workspace) or onboard (on the arm)")
      ->type_name("global|onboard")
      ->capture_default_str();
  cmd.add_option("--resolution", a.resolution, "Global camera image size")->type_name("WxH")->capture_default_str();
  cmd.add_option("--distance", a.distance, "Global camera: distance from the workspace centre, mm")
      ->check(CLI::Range(10.0, 1e6))
      ->capture_default_str();
  cmd.add_option("--tilt", a.tilt, "Global camera: optical axis from vertical, degrees")
      ->check(CLI::Range(0.0, 60.0))
      ->capture_default_str();
  cmd.add_option("--tilt-azimuth", a.tilt_azimuth, "Global camera: direction it leans towards, degrees from East")
      ->capture_default_str();
  cmd.add_option("--roll", a.roll, "Global camera: turn about the optical axis, degrees")->capture_default_str();
  cmd.add_option("--window", a.window, "Onboard camera: view window side a, mm")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();

  // How real: a preset, then each effect on its own (docs/simulator.md has the preset table).
  cmd.add_option("--realism", a.realism,
                 "ideal: today's images (flat disks, OpenCV's lens, gradient, Gaussian noise: what the project's "
                 "models fit exactly); rig: spheres under a point light (shading, highlights, shadows), textured "
                 "table, a lens beyond OpenCV's model, vignetting, defocus towards the corners, shot and read noise, "
                 "PRNU; harsh: all of it stronger, interlaced. The options below override the preset")
      ->check(CLI::IsMember({"ideal", "rig", "harsh"}))
      ->type_name("ideal|rig|harsh")
      ->capture_default_str();
  cmd.add_option("--light", a.light,
                 "Point light position, mm (rig: above the north-west corner 1500 mm up; harsh: 700 mm up; "
                 "ideal: none, uniform light)")
      ->type_name("X,Y,Z");
  cmd.add_flag("--no-light", a.no_light, "Uniform light: no shading, highlights or shadows");
  cmd.add_option("--ambient", a.ambient, "Share of full light every surface gets, 0..1 (rig 0.45, harsh 0.4)")
      ->type_name("A");
  cmd.add_option("--specular", a.specular, "Peak of a marble's highlight, gray levels; 0: none (rig 35, harsh 90)")
      ->type_name("S");
  cmd.add_option("--shininess", a.shininess, "Highlight exponent (Blinn-Phong): larger, smaller (rig 60, harsh 40)")
      ->type_name("P");
  cmd.add_flag("--no-shadows", a.no_shadows, "Marbles cast no shadows");
  cmd.add_option("--texture", a.texture,
                 "Table texture amplitude, fraction of its gray; 0: uniform (rig 0.05, harsh 0.1)")
      ->type_name("C");
  cmd.add_option("--distortion", a.distortion,
                 "Lens k1,k2,p1,p2,k3, OpenCV's terms (global: -0.06,0.015,0.0004,-0.0003,0, harsh stronger; onboard: "
                 "none under ideal, -0.012 rig)")
      ->type_name("K1,K2,P1,P2,K3");
  cmd.add_option("--lens-extra", a.lens_extra,
                 "Lens terms beyond OpenCV's: radial k4 r^8 (times x, y), thin prism x += s1 r^2 + s2 r^4, "
                 "y += s3 r^2 + s4 r^4 (global rig 5,5e-4,-4e-3,-4e-4,3.5e-3; 0 under ideal)")
      ->type_name("K4,S1,S2,S3,S4");
  cmd.add_option("--vignetting", a.vignetting,
                 "Light lost at the image corners, fraction (rig 0.12 global, 0.08 onboard)")
      ->type_name("V");
  cmd.add_option("--blur", a.blur,
                 "Blur sigma at the image centre, px; 0: sharp (ideal 0.7, rig 0.7 global, 0.8 onboard)")
      ->type_name("S");
  cmd.add_option("--defocus", a.defocus,
                 "Blur sigma at the image corners, px, growing from --blur as the square of the radius "
                 "(rig 1.1 global, 1.3 onboard; ideal: as --blur)")
      ->type_name("S");
  cmd.add_option("--noise,--read-noise", a.noise, "Read noise sigma, gray levels; 0: none (ideal 2, rig 1.5, harsh 3)")
      ->type_name("S");
  cmd.add_option("--full-well", a.full_well,
                 "Electrons at gray 255: shot noise variance = gray x 255 / E (rig 12000, harsh 4000; ideal: none)")
      ->type_name("E");
  cmd.add_flag("--no-shot-noise", a.no_shot_noise, "No photon shot noise");
  cmd.add_option("--prnu", a.prnu, "Per-pixel gain sigma, fixed per camera and seed (rig 0.01, harsh 0.02)")
      ->type_name("P");
  cmd.add_option("--gradient", a.gradient,
                 "Illumination gradient, +- fraction across the image (ideal 0.15; rig and harsh 0: the light's own)")
      ->type_name("G");
  cmd.add_flag("--interlace", a.interlace, "Odd rows taken half a frame after the even ones (harsh's default)");
  cmd.add_flag("--no-interlace", a.no_interlace, "Progressive frames");
  cmd.add_option("--seed", a.seed, "Noise and PRNU seed: same seed, same pixels")->capture_default_str();
}

CLI::App* add_sim_command(CLI::App& parent, SimArgs& a) {
  CLI::App* sim = parent.add_subcommand(
      "sim",
      "Simulator: make worlds, render camera frames and videos, drive the arm, look around with the panoramic sensor");
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
  render
      ->add_option("--truth", a.render.cam.truth,
                   "CSV id,u,v,u0,v0: where each visible marble's centre (u,v) and its contact point with the table "
                   "(u0,v0) project (px; the same for ideal's flat disks)")
      ->type_name("truth.csv");
  render
      ->add_option("--camera-out", a.render.camera_out,
                   "The camera's true intrinsics and pose (OpenCV FileStorage YAML), to check a calibration; the lens "
                   "terms beyond OpenCV's five under extra_distortion_coefficients (k4,s1,s2,s3,s4)")
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
                   "Target origin x,y,z (mm), turn theta, tilts about its axes (degrees; default 40,40,0,0,0,0); the "
                   "printed face's: a board t mm thick lying flat has z = t")
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
  video
      ->add_option("--truth", a.video.cam.truth,
                   "CSV frame,id,u,v,u0,v0: projected marble centres and contact points per frame (the even rows' "
                   "instant of an interlaced frame)")
      ->type_name("truth.csv");
  video
      ->add_option("--codec", a.video.codec,
                   "Lossy compression of each frame before writing: none, or jpeg (baseline JPEG's loss, as Motion "
                   "JPEG records; ideal none, rig jpeg 90, harsh jpeg 50). The file's own codec (by extension) "
                   "comes on top")
      ->check(CLI::IsMember({"none", "jpeg"}))
      ->type_name("none|jpeg");
  video->add_option("--quality", a.video.quality, "JPEG quality 1..100 (IJG scale) for --codec jpeg")
      ->check(CLI::Range(1, 100))
      ->type_name("Q");
  video->add_flag("-q,--quiet", a.video.quiet, "No progress bar");

  CLI::App* arm =
      sim->add_subcommand("arm", "Drive the SCARA arm through tool-frame moves; report commanded vs actual poses");
  add_sim_arm_options(*arm, a.arm);

  CLI::App* panorama = sim->add_subcommand(
      "panorama", "The panoramic sensor's ring image at a tool pose, and what a navigator reads from it");
  add_sim_panorama_options(*panorama, a.panorama);
  return sim;
}

int sim_command(const CLI::App& sim, const SimArgs& a) {
  if (sim.got_subcommand("world")) return world_command(a.world);
  if (sim.got_subcommand("render")) return sim_render_command(a.render);
  if (sim.got_subcommand("video")) return sim_video_command(a.video);
  if (sim.got_subcommand("arm")) return sim_arm_command(a.arm);
  if (sim.got_subcommand("panorama")) return sim_panorama_command(a.panorama);
  return kExitUsage;
}

}  // namespace neopipe::apps
