function solve_peers(spec_file)
  % Runs Octave's solvers on one scene for analysis/peers/octave_peer.py: the
  % spec (JSON) names the library, the scene, the output times, the methods
  % and tolerances; the result (JSON) and each solve's states at the output
  % times (binary doubles, 14 per time) are written where the spec says.
  spec = jsondecode(fileread(spec_file));
  rb_problem("load", spec.library);
  [id, name, t_end, y0] = rb_problem("open", spec.scene, spec.t_end);
  times = reshape(spec.times, 1, []);
  result.name = name;
  result.t_end = t_end;
  result.octave = version();
  result.rhs_cost = bare_costs(id, y0, spec.rhs_calls);
  methods = cellstr(spec.methods);
  runs = {};
  for m = 1:numel(methods)
    for tol = reshape(spec.tols, 1, [])
      runs{end + 1} = solve_one(id, methods{m}, tol, y0, t_end, times, spec.repeats, spec.out_dir, numel(runs));
    end
  end
  result.runs = runs;
  rb_problem("close", id);
  fid = fopen(spec.result_file, "w");
  fputs(fid, jsonencode(result));
  fclose(fid);
end

function cost = bare_costs(id, y0, calls)
  % seconds per rhs and Jacobian call through the oct-file, for readers to subtract
  rb_problem("rhs", id, 0, y0);
  tic;
  for k = 1:calls
    rb_problem("rhs", id, 0, y0);
  end
  cost.calls = calls;
  cost.interpreter_s_per_call = toc / calls;
  cost.jacobian_calls = max(1, floor(calls / 10));
  tic;
  for k = 1:cost.jacobian_calls
    rb_problem("jacobian", id, 0, y0);
  end
  cost.jacobian_s_per_call = toc / cost.jacobian_calls;
  rb_problem("reset", id);
end

function opts = options_of(id, method, tol)
  opts = odeset("RelTol", tol, "AbsTol", tol);
  if strcmp(method, "ode15s")
    opts = odeset(opts, "Jacobian", @(t, y) rb_problem("jacobian", id, t, y));
  end
end

function [t, y, status, message] = solve(id, method, tol, y0, tspan)
  % one solve; a solver that stops early or raises is a failed run, not a crash
  f = @(t, y) rb_problem("rhs", id, t, y);
  status = "ok";
  message = "";
  lastwarn("");
  try
    [t, y] = feval(method, f, tspan, y0, options_of(id, method, tol));
  catch err
    t = [];
    y = zeros(0, numel(y0));
    status = "error";
    message = err.message;
  end
  if strcmp(status, "ok") && (numel(t) < numel(tspan) || t(end) < tspan(end))
    status = "error";
    message = lastwarn();
  end
  if ! strcmp(status, "ok")
    if ! isempty(regexpi(message, "step ?size|hmin"))
      status = "step-underflow";
    end
    message = [method ": " strtrim(message)];
  end
end

function run = solve_one(id, method, tol, y0, t_end, times, repeats, out_dir, index)
  rb_problem("reset", id);
  [t, y, status, message] = solve(id, method, tol, y0, [0 times]);
  [rhs_evals, jacobian_evals, beyond] = rb_problem("counts", id);
  % the steps: a solve without output times takes the same steps where it
  % makes the same evaluations (ode45, ode23); IDA (ode15s) stops at each
  % output time, so its steps there are not the timed solve's
  rb_problem("reset", id);
  steps = -1;
  try
    sol = feval(method, @(s, x) rb_problem("rhs", id, s, x), [0 t_end], y0, options_of(id, method, tol));
    steps = numel(sol.x) - 1;
  catch
  end
  untimed_rhs_evals = rb_problem("counts", id);
  wall = zeros(1, repeats);
  for r = 1:repeats
    tic;
    solve(id, method, tol, y0, [0 times]);
    wall(r) = toc;
  end
  rb_problem("reset", id);
  states = sprintf("states-%d.bin", index);
  fid = fopen(fullfile(out_dir, states), "w");
  fwrite(fid, transpose(y(2:end, :)), "double");  % the outputs after the start, time by time
  fclose(fid);
  run = struct("method", method, "tol", tol, "status", status, "message", message, "outputs", max(0, numel(t) - 1),
               "t_reached", ifelse_last(t), "rhs_evals", rhs_evals, "jacobian_evals", jacobian_evals,
               "beyond", beyond, "steps", steps, "untimed_rhs_evals", untimed_rhs_evals, "wall_s", wall,
               "states", states);
end

function v = ifelse_last(t)
  if isempty(t)
    v = 0;
  else
    v = t(end);
  end
end
