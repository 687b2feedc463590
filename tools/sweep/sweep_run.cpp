#include "tools/sweep/sweep_run.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <thread>

#include "core/file_util.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace tumble::tools::sweep {

std::string shellQuote(const std::string& s) {
  bool plain = !s.empty();
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || std::string_view("@%+=:,./_-").find(c) != std::string_view::npos))
      plain = false;
  if (plain) return s;
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string ownBinDir() {
  std::error_code ec;
  fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string(".") : self.parent_path().string();
}

namespace {

json jobJson(const Job& job) {
  json values = json::object();
  for (const SetValue& v : job.values) values[v.key] = v.text;
  return {{"id", job.id},
          {"scenario", job.scenario},
          {"values", values},
          {"seed", job.seed},
          {"integrator", job.integrator},
          {"dt", job.dt_s},
          {"substeps", job.substeps},
          {"argv", job.argv},
          {"report", job.reportPath}};
}

std::string slurmScript(const std::string& dir, const std::string& name, std::size_t jobs, int chunk, std::size_t tasks,
                        const std::string& binDir) {
  std::string s = "#!/bin/bash\n";
  s += "# Slurm job array for the sweep '" + name + "': " + std::to_string(jobs) + " runs in " + std::to_string(tasks) +
       " array tasks of up to " + std::to_string(chunk) + " runs each.\n";
  s += "# Submit with:  sbatch " + shellQuote(dir + "/slurm.sh") + "   (add --wait to block until it ends)\n";
  s += "# Each task runs its chunk one run after the other; finished runs (a report in\n";
  s += "# runs/ID/) are skipped, so submitting again resumes. The sweep folder and\n";
  s += "# the binaries must be on a file system every node sees. Then:\n";
  s += "#   tumble sweep collect " + shellQuote(dir) + "\n";
  s += "#SBATCH --job-name=" + shellQuote("tumble-sweep-" + name) + "\n";
  s += "#SBATCH --array=0-" + std::to_string(tasks - 1) + "\n";
  s += "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n";
  s += "#SBATCH --output=" + shellQuote(dir + "/slurm/task-%A_%a.out") + "\n";
  s += "exec " + shellQuote(binDir + "/tumble-sweep") + " exec " + shellQuote(dir) + " --chunk \"$SLURM_ARRAY_TASK_ID\"\n";
  return s;
}

std::string k8sManifest(const std::string& name, std::size_t jobs, int chunk, std::size_t tasks, const WriteOptions& o) {
  // Kubernetes names: lower case letters, digits and '-'.
  std::string kname = "tumble-sweep-";
  for (char c : name) kname += std::isalnum(static_cast<unsigned char>(c)) ? char(std::tolower(c)) : '-';
  if (kname.size() > 52) kname.resize(52);
  while (kname.back() == '-') kname.pop_back();
  const std::size_t parallelism = std::min<std::size_t>(tasks, std::size_t(std::max(1, o.parallelism)));
  std::string y;
  y += "# Kubernetes indexed Job for the sweep '" + name + "': " + std::to_string(jobs) + " runs in " +
       std::to_string(tasks) + " indexes of up to " + std::to_string(chunk) + " runs.\n";
  y += "# The image is built from tools/sweep/Dockerfile; the sweep folder is on the\n";
  y += "# PersistentVolumeClaim '" + o.volumeClaim + "', mounted at /sweep (copy this folder there).\n";
  y += "# kubectl apply -f k8s-job.yaml; then, with the folder back: tumble sweep collect DIR\n";
  y += "apiVersion: batch/v1\nkind: Job\nmetadata:\n  name: " + kname + "\n";
  y += "spec:\n  completionMode: Indexed\n";
  y += "  completions: " + std::to_string(tasks) + "\n";
  y += "  parallelism: " + std::to_string(parallelism) + "\n";
  // A failed index is retried (up to twice per index on average); a retry
  // skips the runs that finished.
  y += "  backoffLimit: " + std::to_string(2 * tasks) + "\n";
  y += "  template:\n    spec:\n      restartPolicy: Never\n      containers:\n";
  y += "        - name: runs\n          image: " + o.image + "\n";
  y += "          command: [\"sh\", \"-c\", \"exec tumble-sweep exec /sweep --chunk \\\"$JOB_COMPLETION_INDEX\\\"\"]\n";
  y += "          resources:\n            requests: {cpu: \"1\", memory: 1Gi}\n";
  y += "          volumeMounts:\n            - {name: sweep, mountPath: /sweep}\n";
  y += "      volumes:\n        - name: sweep\n          persistentVolumeClaim: {claimName: " + o.volumeClaim + "}\n";
  return y;
}

std::string utcNow() {
  std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

}  // namespace

std::string reportReason(const json& r) {
  std::string reason;
  if (r.contains("script_errors") && !r["script_errors"].empty()) {
    const json& e = r["script_errors"][0];
    reason = "script error: " + e.value("file", std::string()) + ":" + std::to_string(e.value("line", 0)) + ": " +
             e.value("message", std::string());
  } else if (r.contains("expectations")) {
    for (const json& e : r["expectations"])
      if (!e.value("ok", true)) reason += (reason.empty() ? "expectation failed: " : "; ") + e.value("name", std::string()) + " = " + e["value"].dump();
  }
  return reason;
}

namespace {

// The last non-empty line of a log (why a run could not start).
std::string lastLogLine(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty() && line.rfind("== ", 0) != 0) last = line;
  return last;
}

}  // namespace

Status writeSweepFolder(const SweepSpec& spec, const std::vector<Job>& jobs, const std::string& dirIn,
                        const WriteOptions& options) {
  const std::string dir = fs::absolute(dirIn).lexically_normal().string();
  int chunk = options.chunkSize > 0 ? options.chunkSize : int((jobs.size() + 999) / 1000);
  chunk = std::max(chunk, 1);
  const std::size_t tasks = (jobs.size() + std::size_t(chunk) - 1) / std::size_t(chunk);
  json j = {{"name", spec.name},
            {"spec", fs::absolute(spec.file).string()},
            {"keys", sweptKeys(spec)},
            {"collect", spec.collect},
            {"error_metric", spec.errorMetric},
            {"chunk_size", chunk},
            {"jobs", json::array()}};
  for (const Job& job : jobs) j["jobs"].push_back(jobJson(job));
  const fs::path file = fs::path(dir) / "sweep.json";
  if (fs::exists(file)) {
    auto old = readSweepFolder(dir);
    if (!old) return makeError(old.error());
    bool same = old->jobs.size() == j["jobs"].size();
    for (std::size_t i = 0; same && i < j["jobs"].size(); ++i) same = old->jobs[i]["argv"] == j["jobs"][i]["argv"];
    if (!same)
      return makeError(dir + " holds another sweep (" + old->name + ", " + std::to_string(old->jobs.size()) +
                       " jobs) whose runs would be mixed with these; choose another --out folder or delete that one");
  }
  std::error_code ec;
  fs::create_directories(fs::path(dir) / "runs", ec);
  fs::create_directories(fs::path(dir) / "slurm", ec);
  if (ec) return makeError(dir + ": cannot create the sweep folder: " + ec.message());
  std::string lines;
  for (const Job& job : jobs) {
    std::string line;
    for (const std::string& a : job.argv) {
      if (!line.empty()) line += ' ';
      line += shellQuote(a);
    }
    lines += line + "\n";
  }
  const std::string binDir = options.binDir.empty() ? ownBinDir() : options.binDir;
  for (auto [name, text] : {std::pair{"sweep.json", j.dump(1) + "\n"}, std::pair{"jobs.txt", lines},
                            std::pair{"slurm.sh", slurmScript(dir, spec.name, jobs.size(), chunk, tasks, binDir)},
                            std::pair{"k8s-job.yaml", k8sManifest(spec.name, jobs.size(), chunk, tasks, options)}}) {
    if (auto st = writeFileAtomic((fs::path(dir) / name).string(), text); !st) return st;
  }
  fs::permissions(fs::path(dir) / "slurm.sh", fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                  fs::perm_options::add, ec);
  return Ok{};
}

Result<SweepFolder> readSweepFolder(const std::string& dirIn) {
  const std::string dir = fs::absolute(dirIn).lexically_normal().string();
  const std::string file = dir + "/sweep.json";
  auto text = readTextFile(file);
  if (!text) return makeError(dir + ": not a sweep folder (no sweep.json; `tumble sweep SPEC --out " + dirIn + "` makes one)");
  SweepFolder s;
  s.dir = dir;
  try {
    json j = json::parse(text.value());
    s.name = j.at("name").get<std::string>();
    s.keys = j.at("keys").get<std::vector<std::string>>();
    s.collect = j.at("collect").get<std::vector<std::string>>();
    s.errorMetric = j.at("error_metric").get<std::string>();
    s.chunkSize = std::max(1, j.at("chunk_size").get<int>());
    s.jobs = j.at("jobs");
    for (const json& job : s.jobs) {
      job.at("id").get<std::string>();
      job.at("argv").get<std::vector<std::string>>();
      job.at("report").get<std::string>();
    }
  } catch (const json::exception& e) {
    return makeError(file + ": damaged (" + std::string(e.what()) + "); write the sweep again with tumble sweep SPEC --out");
  }
  return s;
}

bool jobFinished(const SweepFolder& sweep, std::size_t index) {
  const std::string path = sweep.dir + "/" + sweep.jobs[index]["report"].get<std::string>();
  auto text = readTextFile(path);
  if (!text) return false;
  json r = json::parse(text.value(), nullptr, false);
  return r.is_object() && r.contains("state_hash") && r["state_hash"].is_string();
}

std::pair<std::size_t, std::size_t> chunkRange(const SweepFolder& sweep, std::size_t chunk) {
  const std::size_t n = sweep.jobs.size(), k = std::size_t(sweep.chunkSize);
  const std::size_t begin = std::min(n, chunk * k);
  return {begin, std::min(n, begin + k)};
}

bool execJob(const SweepFolder& sweep, std::size_t index, const std::string& tumbleBinary) {
  if (jobFinished(sweep, index)) return true;  // resume: done before
  const json& job = sweep.jobs[index];
  const std::string id = job["id"].get<std::string>();
  const fs::path runDir = fs::path(sweep.dir) / "runs" / id;
  std::error_code ec;
  fs::create_directories(runDir, ec);
  const std::string logPath = (runDir / "log.txt").string();
  std::vector<std::string> argv = job["argv"].get<std::vector<std::string>>();
  argv[0] = tumbleBinary;
  std::string shown;
  for (const json& a : job["argv"]) {
    if (!shown.empty()) shown += ' ';
    shown += shellQuote(a.get<std::string>());
  }
  {
    std::ofstream log(logPath, std::ios::app);
    log << "== " << utcNow() << " in " << sweep.dir << ": " << shown << "\n";
  }
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = fork();
  if (pid == 0) {
    int fd = open(logPath.c_str(), O_WRONLY | O_APPEND | O_CREAT, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
      close(fd);
    }
    if (chdir(sweep.dir.c_str()) != 0) _exit(127);
    std::vector<char*> args;
    for (std::string& a : argv) args.push_back(a.data());
    args.push_back(nullptr);
    execv(args[0], args.data());
    std::fprintf(stderr, "cannot start %s: %s\n", args[0], std::strerror(errno));
    _exit(127);
  }
  int status = 0;
  if (pid < 0 || waitpid(pid, &status, 0) < 0) status = -1;
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  json st = {{"id", id}, {"wall_seconds", wall_s}, {"exit", nullptr}, {"signal", nullptr}, {"finished_at", utcNow()}};
  const bool finished = jobFinished(sweep, index);
  std::string reason;
  if (pid < 0 || status == -1) reason = "could not start a process: " + std::string(std::strerror(errno));
  else if (WIFSIGNALED(status)) {
    st["signal"] = WTERMSIG(status);
    reason = "killed by signal " + std::to_string(WTERMSIG(status)) + " (" + strsignal(WTERMSIG(status)) + ")";
  } else {
    st["exit"] = WEXITSTATUS(status);
    if (finished) {
      auto text = readTextFile(sweep.dir + "/" + job["report"].get<std::string>());
      reason = reportReason(json::parse(text.value(), nullptr, false));
    } else {
      reason = "exit " + std::to_string(WEXITSTATUS(status)) + " without a report: " + lastLogLine(logPath);
    }
  }
  st["reason"] = reason;
  (void)writeFileAtomic((runDir / "status.json").string(), st.dump(1) + "\n");
  if (!finished) std::fprintf(stderr, "sweep: job %s failed: %s (log: %s)\n", id.c_str(), reason.c_str(), logPath.c_str());
  return finished;
}

json jobStatus(const SweepFolder& sweep, std::size_t index) {
  const std::string id = sweep.jobs[index]["id"].get<std::string>();
  const std::string runDir = sweep.dir + "/runs/" + id;
  if (auto text = readTextFile(runDir + "/status.json"); text) {
    json st = json::parse(text.value(), nullptr, false);
    if (st.is_object()) return st;
  }
  // A local run through GNU parallel leaves the shell's exit status in
  // runs/<id>/exit (128 + N: killed by signal N).
  auto text = readTextFile(runDir + "/exit");
  if (!text) return nullptr;
  const int code = std::atoi(text.value().c_str());
  json st = {{"id", id}, {"exit", nullptr}, {"signal", nullptr}};
  // runs/<id>/time: the run's start and end, s (bash's $EPOCHREALTIME).
  if (auto times = readTextFile(runDir + "/time"); times) {
    double t0 = 0, t1 = 0;
    if (std::sscanf(times.value().c_str(), "%lf %lf", &t0, &t1) == 2 && t1 >= t0) st["wall_seconds"] = t1 - t0;
  }
  if (code > 128) st["signal"] = code - 128;
  else st["exit"] = code;
  if (jobFinished(sweep, index)) {
    st["reason"] = reportReason(json::parse(readTextFile(sweep.dir + "/" + sweep.jobs[index]["report"].get<std::string>()).value(), nullptr, false));
  } else {
    st["reason"] = code > 128 ? "killed by signal " + std::to_string(code - 128) + " (" + strsignal(code - 128) + ")"
                              : "exit " + std::to_string(code) + " without a report: " + lastLogLine(runDir + "/log.txt");
  }
  return st;
}

std::string outcomeSummary(const SweepFolder& sweep, int* exitStatus) {
  int passed = 0, expectation = 0, script = 0, failed = 0, notRun = 0;
  for (std::size_t i = 0; i < sweep.jobs.size(); ++i) {
    const std::string id = sweep.jobs[i]["id"].get<std::string>();
    if (jobFinished(sweep, i)) {
      auto text = readTextFile(sweep.dir + "/" + sweep.jobs[i]["report"].get<std::string>());
      json r = json::parse(text.value(), nullptr, false);
      if (!r["script_errors"].empty()) ++script;
      else if (!reportReason(r).empty()) ++expectation;
      else ++passed;
    } else if (!jobStatus(sweep, i).is_null()) {
      ++failed;
    } else {
      ++notRun;
    }
  }
  *exitStatus = failed + notRun > 0 ? 1 : (expectation + script > 0 ? 2 : 0);
  char buf[256];
  std::snprintf(buf, sizeof buf, "%zu jobs: %d passed, %d failed an expectation, %d had a script error, %d failed to run, %d not run",
                sweep.jobs.size(), passed, expectation, script, failed, notRun);
  return buf;
}

int runLocal(const SweepFolder& sweep, int jobsAtOnce, int runsPerJob, double timeout_s, const std::string& tumbleBinary) {
  // GNU parallel runs batches of runs, one bash line a batch. Each run in a
  // batch appends its output to runs/<id>/log.txt (earlier attempts stay
  // above it), and leaves its exit status in runs/<id>/exit and its start
  // and end (bash's $EPOCHREALTIME, no extra process) in runs/<id>/time.
  // Why batches: a short run costs about as much as starting a process, and
  // GNU parallel (Perl) plus the shell it starts add about 20 ms a job
  // outside the run; a batch pays that once for several runs. Batches are
  // small enough (32 per slot) that the slots finish close together.
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < sweep.jobs.size(); ++i) {
    if (jobFinished(sweep, i)) continue;
    const json& job = sweep.jobs[i];
    const std::string run = "runs/" + job["id"].get<std::string>();
    std::string command = shellQuote(tumbleBinary);
    const auto argv = job["argv"].get<std::vector<std::string>>();
    for (std::size_t a = 1; a < argv.size(); ++a) {
      command += ' ';
      command += shellQuote(argv[a]);
    }
    // The folder is made and a stale exit status removed here, so the line
    // runs no program but tumble.
    std::error_code ec;
    fs::create_directories(sweep.dir + "/" + run, ec);
    fs::remove(sweep.dir + "/" + run + "/exit", ec);
    fs::remove(sweep.dir + "/" + run + "/time", ec);
    // --timeout: coreutils timeout stops the run (TERM, then KILL 5 s later)
    // and exits 124; the log says so, and that line becomes the reason.
    std::string timed = command, onTimeout;
    if (timeout_s > 0) {
      char t[64];
      std::snprintf(t, sizeof t, "%g", timeout_s);
      timed = std::string("timeout -k 5 ") + t + " " + command;
      onTimeout = std::string("; [ $s = 124 ] && echo 'stopped by the sweep: ran longer than --timeout ") + t + " s' >> " + run +
                  "/log.txt";
    }
    lines.push_back("echo " + shellQuote("== " + command) + " >> " + run + "/log.txt; t0=$EPOCHREALTIME; " + timed +
                    " >> " + run + "/log.txt 2>&1; s=$?; echo \"$t0 $EPOCHREALTIME\" > " + run + "/time" + onTimeout +
                    "; echo $s > " + run + "/exit; [ $s -gt $worst ] && worst=$s");
  }
  const std::size_t todo = lines.size();
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t slots = jobsAtOnce > 0 ? static_cast<std::size_t>(jobsAtOnce) : cores;
  const std::size_t batch = runsPerJob > 0 ? static_cast<std::size_t>(runsPerJob) : std::max<std::size_t>(1, todo / (slots * 32));
  std::string pending;
  for (std::size_t i = 0; i < todo; i += batch) {
    pending += "cd " + shellQuote(sweep.dir) + " || exit 1; worst=0";
    for (std::size_t k = i; k < std::min(todo, i + batch); ++k) pending += "; " + lines[k];
    pending += "; exit $worst\n";
  }
  const std::size_t done = sweep.jobs.size() - todo;
  if (todo == 0) {
    std::printf("sweep %s: all %zu jobs finished already (nothing to run)\n", sweep.name.c_str(), sweep.jobs.size());
  } else {
    std::printf("sweep %s: %zu of %zu jobs to run (%zu finished before are skipped), %zu at a time in batches of %zu\n",
                sweep.name.c_str(), todo, sweep.jobs.size(), done, slots, batch);
    std::fflush(stdout);
    const std::string list = sweep.dir + "/pending.txt";
    if (auto st = writeFileAtomic(list, pending); !st) {
      std::fprintf(stderr, "sweep: %s\n", st.error().c_str());
      return 1;
    }
    if (std::system("command -v parallel >/dev/null 2>&1") != 0) {
      std::fprintf(stderr, "sweep: GNU parallel is not installed (Debian: apt-get install parallel; tools/tumble installs it)\n");
      return 1;
    }
    // The progress bar and ETA on a terminal; in a log (CI, nohup) they
    // would be thousands of redrawn lines, and the joblog has the record.
    // --joblog +FILE appends, so earlier attempts stay on record.
    const bool terminal = isatty(2) != 0;
    std::string cmd = std::string("PARALLEL_SHELL=/bin/bash parallel --will-cite ") + (terminal ? "--bar --eta " : "") + "--joblog +" +
                      shellQuote(sweep.dir + "/joblog.txt") + " -j " +
                      std::to_string(slots) + " :::: " + shellQuote(list);
    (void)std::system(cmd.c_str());
  }
  int status = 0;
  std::printf("sweep %s: %s\n", sweep.name.c_str(), outcomeSummary(sweep, &status).c_str());
  return status;
}

}  // namespace tumble::tools::sweep
