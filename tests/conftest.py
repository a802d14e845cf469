"""Shared test helpers."""
import json

import pytest

from pendulab.cli import main

#: Test files whose every test takes seconds (a server or a CLI in a subprocess, the
#: browser, Typst, Sphinx, a notebook kernel, ruff and mypy): the slow tier. ``make check``
#: runs the others (``-m "not slow"``) and ruff and mypy directly; ``make test`` runs all.
SLOW_FILES = frozenset({
    "test_boundary_cli.py", "test_docs.py", "test_lint.py", "test_notebook.py", "test_packaging.py",
    "test_report.py", "test_web_e2e.py", "test_web_load.py", "test_web_server.py",
})


#: Single tests of the other files that take seconds (measured with ``--durations``): a
#: large search, a CLI in a subprocess, a figure saved as PDF, a Dask cluster. Each entry is
#: ``file::test`` and covers every parametrisation of that test.
SLOW_TESTS = frozenset({
    "test_interrupt.py::test_ctrl_c_mid_run_ends_with_one_line_and_130",
    "test_interrupt.py::test_sigterm_mid_run_ends_with_one_line_and_143",
    "test_interrupt.py::test_an_interrupted_key_keeps_the_old_output_and_leaves_no_temporary_file",
    "test_interrupt.py::test_sigterm_during_report_leaves_no_temporary_folder",
    "test_interrupt.py::test_a_signal_between_the_key_and_its_class_file_waits_for_both",
    "test_interrupt.py::test_ctrl_c_while_the_command_line_loads_is_one_line",
    "test_interrupt.py::test_a_signal_while_a_kernel_compiles_ends_the_run",
    "test_interrupt.py::test_a_signal_stops_a_long_sweep_on_threads_within_seconds",
    "test_interrupt.py::test_ctrl_c_while_a_cold_sweep_compiles_ends_with_one_line",
    "test_interrupt.py::test_a_signal_during_the_servers_warm_up_stops_it_with_its_line",
    "test_hostile_env.py::test_groups_from_a_named_pipe_with_no_writer_do_not_hang",
    "test_hostile_env.py::test_endless_standard_input_is_capped",
    "test_hostile_env.py::test_groups_from_standard_input",
    "test_hostile_env.py::test_a_full_disk_on_stdout_is_one_line",
    "test_hostile_env.py::test_a_closed_pipe_on_stdout_is_one_line",
    "test_hostile_env.py::test_a_read_only_install_falls_back_and_a_corrupt_cache_is_rebuilt",
    "test_hostile_env.py::test_a_scheduler_port_that_is_not_dask_is_one_line",
    "test_agm_rounding.py::test_extreme_lengths_and_g_give_representable_periods",
    "test_agm_rounding.py::test_2000_random_pendulums_are_correctly_rounded",
    "test_agm_rounding.py::test_half_angle_cos_is_accurate_to_double_double",
    "test_approximations.py::test_cli_approximations",
    "test_approximations.py::test_plot_draws_each_formulas_errors",
    "test_bounds_adversarial.py::test_docs_table_states_what_a_quick_run_states",
    "test_bounds_adversarial.py::test_every_search_stays_within_its_bound",
    "test_bounds_adversarial.py::test_significant_digits_is_the_exact_rule_near_powers_of_ten_and_ties",
    "test_boundary_web.py::test_several_hostile_values_at_once",
    "test_boundary_web.py::test_hostile_value_in_any_parameter",
    "test_boundary_web.py::test_long_periods_are_answered_without_an_estimate",
    "test_cli_core.py::test_figures_leave_matplotlib_global_state_alone",
    "test_cli_core.py::test_simulate_figures",
    "test_cli_problems.py::test_fit_json_and_plot",
    "test_crossing.py::test_flow_series_is_the_solution_of_the_ode",
    "test_crossing.py::test_streamed_search_equals_search_on_the_stored_trajectory",
    "test_fast_step.py::test_fast_step_equals_the_literal_step_along_trajectories",
    "test_fast_step.py::test_first_return_equals_the_python_loop",
    "test_fast_step.py::test_table_sin_cos_within_a_quarter_of_the_margins_of_the_c_library",
    "test_fast_step.py::test_table_sin_cos_error_against_mpmath",
    "test_fast_step.py::test_fallback_rate_at_problem_3",
    "test_group.py::test_length_is_the_correctly_rounded_geometric_mean",
    "test_inputs.py::test_every_parser_returns_or_raises_one_line",
    "test_key.py::test_cli_csv_is_a_plain_table",
    "test_key.py::test_cli_pdf_has_the_class_page_and_names",
    "test_motion.py::test_exact_motion_within_its_bound_densely",
    "test_period_certified.py::test_int_text_prints_any_length",
    "test_period_certified.py::test_decimal_text_is_mpmath_nstr_layout",
    "test_period_certified.py::test_ball_always_contains_the_period",
    "test_programs.py::test_each_program_runs_without_pendulab",
    "test_quadrature.py::test_ten_million_subintervals_in_bounded_memory",
    "test_report_sentences.py::test_names_on_the_cover",
    "test_report_sentences.py::test_up_is_never_below_and_within_one_unit",
    "test_report_sentences.py::test_two_periods_print_equal_only_when_equal",
    "test_report_sentences.py::test_3b_says_where_t_hat_lies_against_the_bracket",
    "test_report_sentences.py::test_a_number_beside_a_threshold_stays_on_its_side",
    "test_quadrature.py::test_singular_sum_nodes_keep_their_distance_to_alpha",
    "test_results.py::test_to_dict_and_to_frame_of_a_trajectory",
    "test_sweep.py::test_sweep_equals_estimate_period_bit_for_bit",
    "test_sweep.py::test_lanes_vectorise",
    "test_sweep.py::test_dask_cluster_gives_the_same_result",
    "test_sweep.py::test_cli_sweep",
    "test_sweep.py::test_unreachable_scheduler_is_one_clear_error",
    "test_web_api.py::test_csv_streams_in_blocks",
    "test_web_api.py::test_long_run_plots_keep_the_shape",
})


def pytest_ignore_collect(collection_path, config):
    """``-m "not slow"`` (``make check``) does not even import the slow files: collecting
    them would import the browser driver, nbformat and pypdf for nothing."""
    if config.getoption("markexpr") == "not slow" and collection_path.name in SLOW_FILES:
        return True
    return None


@pytest.hookimpl(tryfirst=True)  # before -m deselects by marker
def pytest_collection_modifyitems(config, items):
    seen = set()
    for item in items:
        test = f"{item.path.name}::{item.originalname}"
        if item.path.name in SLOW_FILES or test in SLOW_TESTS:
            item.add_marker(pytest.mark.slow)
            seen.add(test)
    # On a run of the whole folder, a listed test that no longer exists is a stale entry.
    if {item.path.name for item in items} >= {name.split("::")[0] for name in SLOW_TESTS}:
        stale = sorted(SLOW_TESTS - seen)
        if stale:
            raise pytest.UsageError(f"tests/conftest.py SLOW_TESTS names tests that do not exist: {stale}")


class Run:
    def __init__(self, code, out, err):
        self.code, self.out, self.err = code, out, err

    @property
    def json(self):
        return json.loads(self.out)


@pytest.fixture
def cli(capsys):
    """Run ``pendulab ARGS`` in-process; return exit code, stdout, stderr."""

    def run(*args):
        code = main([str(a) for a in args])
        captured = capsys.readouterr()
        return Run(code, captured.out, captured.err)

    return run


def assert_one_line_error(res, *fragments):
    """Exit status 2, one line on stderr naming what is wrong, no traceback."""
    assert res.code == 2, (res.out, res.err)
    lines = res.err.strip().splitlines()
    assert len(lines) == 1, res.err
    assert "Traceback" not in res.err
    for f in fragments:
        assert f in lines[0], (f, lines[0])
