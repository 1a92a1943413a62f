// The panel's advice (demos/gui/advice_job.h): `particle-lab advise` for the
// current scene, run off the main thread with a progress bar, cancel, and
// Apply, all driven by scripted clicks and typing.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "demo_driver.h"

using namespace demotest;

namespace {

// A scripted click at a point of a widget: the pointer moves there a frame
// before the press (so that ImGui knows it is over the panel), the release a
// frame after. `along` is the fraction of the widget's width from its left
// edge (an input field's box is at its left, its label at the right).
std::string clickAt(long long frame, const LoggedOverlay& w, double along = 0.5) {
  std::ostringstream s;
  const double x = w.x + along * w.width, y = w.y + 0.5 * w.height;
  s << frame << " move window " << x << " " << y << "\n"
    << frame + 1 << " down window " << x << " " << y << "\n"
    << frame + 2 << " up window " << x << " " << y << "\n";
  return s.str();
}

// Clicking a numeric field selects its text, so the typed value replaces it.
std::string typeInto(long long frame, const LoggedOverlay& w, const std::string& text) {
  std::string s = clickAt(frame, w, 0.1);
  for (std::size_t k = 0; k < text.size(); ++k) s += std::to_string(frame + 4 + k) + " key " + text[k] + "\n";
  return s;
}

// The panel's advice section, opened by a click on its header: where its
// fields and buttons are.
StateLog adviceLayout(const std::string& dir, const std::string& scene) {
  const std::string window = " --window 1180x1010";
  EXPECT_EQ(runDemo(dir, "--scene " + scene + window + " --frames 2 --log-state closed.txt").exitCode, 0);
  const StateLog closed = readStateLog(dir + "/closed.txt");
  const LoggedOverlay* header = closed.widget("advice");
  EXPECT_NE(header, nullptr) << "the panel has an advice section";
  if (!header) return {};
  EXPECT_EQ(runDemo(dir, "--scene " + scene + window + " --frames 8 --log-state open.txt", clickAt(2, *header)).exitCode, 0);
  return readStateLog(dir + "/open.txt");
}

}  // namespace

TEST(DemoAdvice, AdviceRunsOffTheMainLoopAndApplySetsTheAdvisedIntegratorAndDt) {
  const std::string dir = outputDirectory("AdviceApply");
  const StateLog layout = adviceLayout(dir, "pendulum");
  for (const char* name : {"advice", "advise-error", "advise-horizon", "advise", "advise-apply"})
    ASSERT_NE(layout.widget(name), nullptr) << name;
  // Start far from any advice (implicit Euler at a tiny dt: it never
  // diverges, so the pane keeps running however long the survey takes; a
  // paused pane's shorter "Run" label would move the panel's rows up), ask
  // for E = 0.01 over T = 5 s, wait for the survey, apply, and run on.
  const std::string script = clickAt(2, *layout.widget("advice")) +
                             typeInto(10, *layout.widget("advise-horizon"), "5") +
                             typeInto(20, *layout.widget("advise-error"), "0.01") +
                             clickAt(30, *layout.widget("advise")) + "34 wait advice\n" +
                             clickAt(40, *layout.widget("advise-apply")) + "60 key q\n";
  const RunResult run = runDemo(dir,
                                "--scene pendulum --window 1180x1010 --integrator implicit-euler --dt 0.001 --frames 1000000 "
                                "--log-state state.txt --screenshot advice.png",
                                script);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const StateLog log = readStateLog(dir + "/state.txt");
  ASSERT_EQ(log.advice.state, "done");
  EXPECT_DOUBLE_EQ(log.advice.progress, 1.0);
  ASSERT_FALSE(log.advice.integrator.empty()) << "the pendulum meets 0.01 over 5 s with some integrator";
  EXPECT_GT(log.advice.dt, 0.001);
  const LoggedPane& pane = log.panes.at(0);
  EXPECT_EQ(pane.integrator, log.advice.integrator);
  EXPECT_EQ(pane.dt, log.advice.dt);
  EXPECT_NE(log.advice.applied.find("--integrator " + log.advice.integrator + " --dt "), std::string::npos)
      << log.advice.applied;
  EXPECT_FALSE(pane.diverged);
  // The survey ran while frames were drawn: the main loop never waited for it.
  EXPECT_GT(log.advice.framesWhileRunning, 0);
  EXPECT_GT(pane.framesAdvanced, 60);
}

TEST(DemoAdvice, CancelStopsTheSurveyAndChangesNothing) {
  const std::string dir = outputDirectory("AdviceCancel");
  const StateLog layout = adviceLayout(dir, "cloth");
  ASSERT_NE(layout.widget("advise-cancel"), nullptr);
  // The window is tall enough for the cloth's parameters and the open advice
  // section together. A survey of the cloth to a tight budget over 30 s takes far longer than
  // the few frames before the cancel.
  const std::string script = clickAt(2, *layout.widget("advice")) +
                             typeInto(10, *layout.widget("advise-horizon"), "30") +
                             typeInto(20, *layout.widget("advise-error"), "1e-7") +
                             clickAt(30, *layout.widget("advise")) + clickAt(36, *layout.widget("advise-cancel")) +
                             "40 wait advice\n" + clickAt(44, *layout.widget("advise-apply")) + "50 key q\n";
  const RunResult run = runDemo(dir, "--scene cloth --window 1180x1010 --frames 1000000 --log-state state.txt", script);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const StateLog log = readStateLog(dir + "/state.txt");
  EXPECT_EQ(log.advice.state, "cancelled");
  EXPECT_LT(log.advice.progress, 1.0);
  EXPECT_TRUE(log.advice.applied.empty()) << "Apply is disabled without a result";
  EXPECT_GE(log.advice.framesWhileRunning, 6);
}

TEST(DemoAdvice, QuittingWhileTheSurveyRunsExitsCleanly) {
  const std::string dir = outputDirectory("AdviceQuit");
  const StateLog layout = adviceLayout(dir, "cloth");
  ASSERT_NE(layout.widget("advise"), nullptr);
  const std::string script = clickAt(2, *layout.widget("advice")) +
                             typeInto(10, *layout.widget("advise-horizon"), "30") +
                             typeInto(20, *layout.widget("advise-error"), "1e-7") +
                             clickAt(30, *layout.widget("advise")) + "40 key q\n";
  const RunResult run = runDemo(dir, "--scene cloth --window 1180x1010 --frames 1000000 --log-state state.txt", script);
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(readStateLog(dir + "/state.txt").advice.state, "running");
}

TEST(DemoAdvice, TheScriptingGuidesAdviceExampleApplies) {
  std::ifstream doc(SCRIPTING_MD);
  std::stringstream text;
  text << doc.rdbuf();
  const std::string all = text.str();
  const auto start = all.find("# advise on the oscillator");
  ASSERT_NE(start, std::string::npos);
  const std::string example = all.substr(start, all.find("```", start) - start);
  const std::string dir = outputDirectory("AdviceScriptingExample");
  const RunResult run =
      runDemo(dir, "--scene oscillator --integrator euler --dt 0.001 --frames 100000 --log-state state.txt", example);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const StateLog log = readStateLog(dir + "/state.txt");
  ASSERT_EQ(log.advice.state, "done");
  EXPECT_EQ(log.panes.at(0).integrator, log.advice.integrator);
  EXPECT_EQ(log.panes.at(0).dt, log.advice.dt);
  EXPECT_NE(log.panes.at(0).integrator, "euler");
}
