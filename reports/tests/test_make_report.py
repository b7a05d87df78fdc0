"""Tests of reports/make_report.py (standard library unittest only).

    /usr/bin/python3 -m unittest discover -s reports/tests

Each test copies the committed fixture (tests/fixtures: synthetic results for two
problems, plus their problem descriptions) to a temporary directory, damages it the
way the test needs, runs make_report.py as a separate process and checks the exit
status, stderr and the page.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path
from unittest import mock

HERE = Path(__file__).resolve().parent
REPORTS = HERE.parent
FIXTURES = HERE / "fixtures"
SCRIPT = REPORTS / "make_report.py"

sys.path.insert(0, str(REPORTS))
from pdreport import numfmt, render  # noqa: E402

# A reference that would make the browser go to the network (independent of the code under test).
NETWORK_REF = re.compile(r"""(?:src|href)\s*=\s*["']?\s*(?:https?:)?//""", re.IGNORECASE)


class ReportTestCase(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="report-test-"))
        self.addCleanup(shutil.rmtree, self.tmp)
        self.results = self.tmp / "results"
        self.problems = self.tmp / "problems"
        shutil.copytree(FIXTURES / "results", self.results)
        shutil.copytree(FIXTURES / "problems", self.problems)
        self.out = self.tmp / "report" / "index.html"

    def run_report(self, *extra, results=None):
        refs = [] if "--references" in extra else ["--references", str(FIXTURES / "references.md")]
        if "--claims" not in extra:
            refs += ["--claims", str(FIXTURES / "claims.toml")]
        args = [sys.executable, str(SCRIPT), "--results", str(results or self.results),
                "--problems", str(self.problems), "--out", str(self.out), *refs, *extra]
        proc = subprocess.run(args, capture_output=True, text=True, timeout=120)
        self.assertNotIn("Traceback", proc.stderr, "bad input must not end in a traceback")
        page = self.out.read_text(encoding="utf-8") if self.out.is_file() else ""
        return proc, page

    def gate_path(self, gate_id):
        return self.results / "gates" / f"{gate_id}.json"

    def edit_json(self, path, **changes):
        obj = json.loads(path.read_text())
        obj.update(changes)
        path.write_text(json.dumps(obj))

    def assert_self_contained(self, page):
        self.assertEqual(NETWORK_REF.findall(page), [], "page refers to a network resource")
        self.assertNotRegex(page, r"<link\b", "no external stylesheets")
        self.assertNotRegex(page, r"<script[^>]*\bsrc=", "no external scripts")

    def assert_one_line_messages(self, stderr):
        for line in stderr.splitlines():
            self.assertTrue(line.startswith("make_report: "), f"unexpected stderr line: {line!r}")


class GoodInputs(ReportTestCase):
    def test_all_pass_gives_status_0_and_a_full_page(self):
        proc, page = self.run_report()
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertEqual(proc.stderr, "")
        self.assertIn(str(self.out), proc.stdout)
        self.assertIn("4 gates: 4 passed, 0 failed, 0 missing, 0 malformed", proc.stdout)
        self.assertIn("ALL GATES PASS", page)
        for path in (self.results / "gates").glob("*.json"):
            gate = json.loads(path.read_text())
            self.assertIn(f'id="gate-{gate["id"]}"', page)      # its row in the main table
            self.assertIn(gate["tolerance_reason"], page)
        for title in ("Fixture: PMB bond constants", "Fixture: vibrating bar",
                      "Lattice sum vs continuum constant", "PMB micromodulus c, 3D, ν = 1/4", "BM_sum/1024_mean"):
            self.assertIn(title, page)
        self.assertNotIn('class="badge MALFORMED"', page)
        self.assertNotIn('class="badge MISSING"', page)
        self.assertGreaterEqual(page.count("data:image/png;base64,"), 3)   # two plots and one image
        self.assert_self_contained(page)

    def test_the_papers_claims_come_first_with_their_verdicts(self):
        proc, page = self.run_report()
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertLess(page.index('id="claims"'), page.index('id="gates"'))
        claims = page[page.index('id="claims"'):page.index('id="gates"')]
        self.assertIn("1.509e+19 N/m⁶", claims)               # the gate's measured value, formatted
        self.assertIn('verdict reproduced">reproduced', claims)
        self.assertIn('verdict deviation-explained">deviation explained', claims)
        self.assertIn("The fixture bar is linear", claims)
        self.assertIn('verdict not-measured">not measured', claims)
        self.assertIn('href="#ref-deryugin2023"', claims)
        self.assertIn('href="#p-fixture_constants"', claims)

    def test_a_failed_gate_makes_its_claim_failed(self):
        self.edit_json(self.gate_path("fixture.constants.pmb3d_closed_form"), measured=2e19)
        _, page = self.run_report()
        claims = page[page.index('id="claims"'):page.index('id="gates"')]
        self.assertIn('verdict failed">failed', claims)

    def test_a_claim_of_a_gate_another_command_records_is_not_run_here(self):
        path = self.problems / "fixture_constants.toml"
        path.write_text(path.read_text() + '\n[recorded_by]\n"fixture.constants.pmb3d_closed_form" = "the full tier"\n')
        self.gate_path("fixture.constants.pmb3d_closed_form").unlink()
        _, page = self.run_report()
        claims = page[page.index('id="claims"'):page.index('id="gates"')]
        self.assertIn('verdict not-run-here">not run here', claims)

    def test_malformed_claims_are_an_issue_not_a_crash(self):
        claims = self.tmp / "claims.toml"
        for text, fragment in (('[[claim]]\npaper = "deryugin2023"\n', "'where' must be a non-empty string"),
                               ('[[claim]]\npaper = "x"\nwhere = "a"\nquantity = "q"\npaper_value = "1"\nmood = 2\n',
                                "unknown key(s) ['mood']"),
                               ('[[claim]]\npaper = "nokey"\nwhere = "a"\nquantity = "q"\npaper_value = "1"\n',
                                "unknown paper key [nokey]"),
                               ('[[claim]]\npaper = "silling2000"\nwhere = "a"\nquantity = "q"\npaper_value = "1"\n'
                                'ours = "{:.2q}"\n', "'ours' is not a format"),
                               ("[[claim\n", "")):
            claims.write_text(text, encoding="utf-8")
            proc, page = self.run_report("--claims", str(claims))
            self.assertEqual(proc.returncode, 1, text)
            self.assertIn("MALFORMED", proc.stderr, text)
            self.assertIn(fragment, proc.stderr, text)
            self.assertIn('id="gates"', page)  # the rest of the page is still there

    def test_gate_table_comes_before_the_problem_sections(self):
        _, page = self.run_report()
        self.assertLess(page.index('id="gates"'), page.index('id="p-fixture_constants"'))
        self.assertLess(page.index('id="p-fixture_constants"'), page.index('id="p-fixture_bar"'))  # toml order

    def test_provenance_is_shown_and_a_dirty_tree_is_highlighted(self):
        _, page = self.run_report()
        for value in ("fixture0000ab", "GNU 12.2.0", "-O3 -fopenmp", "Fixture CPU @ 2.6GHz"):
            self.assertIn(value, page)
        self.assertNotIn("DIRTY", page)
        self.edit_json(self.results / "provenance.json", tree="dirty")
        _, page = self.run_report()
        self.assertIn('class="badge dirty"', page)
        self.assertIn("DIRTY", page)

    def test_the_instruction_set_is_shown_when_recorded(self):
        _, page = self.run_report()
        self.assertNotIn("vector instructions", page)  # the fixture's provenance predates the key
        self.edit_json(self.results / "provenance.json", simd="avx2")
        _, page = self.run_report()
        self.assertIn("<dd>avx2 (PD kernels and MPM lanes)</dd>", page)

    def test_same_input_gives_the_same_page(self):
        self.run_report()
        first = self.out.read_bytes()
        self.run_report()
        self.assertEqual(first, self.out.read_bytes())

    def test_missing_benchmarks_are_noted_but_not_an_error(self):
        shutil.rmtree(self.results / "bench")
        proc, page = self.run_report()
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertIn("No benchmark results", page)


class PlotOptions(ReportTestCase):
    def test_error_bars_and_category_ticks_render(self):
        path = self.results / "data" / "fixture_bar" / "04_bars.json"
        path.write_text(json.dumps({"kind": "plot", "title": "Rates with intervals", "yscale": "log",
                                    "xticks": {"values": [1, 2], "labels": ["PMB", "LPS"]},
                                    "series": [{"label": "a", "x": [1, 2], "y": [3e8, 1e8], "style": "points",
                                                "ylo": [2.5e8, None], "yhi": [3.5e8, None]}]}))
        proc, page = self.run_report()
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertIn("Rates with intervals", page)
        self.assertGreaterEqual(page.count("data:image/png;base64,"), 4)


class FailingGates(ReportTestCase):
    def test_failed_gate_gives_status_1_and_a_red_row(self):
        gid = "fixture.bar.convergence_order"
        self.edit_json(self.gate_path(gid), measured=1.2, verdict="FAIL")
        proc, page = self.run_report()
        self.assertEqual(proc.returncode, 1)
        self.assertIn("1 failed", proc.stdout)
        self.assertIn(f"FAIL: {self.gate_path(gid)}", proc.stderr)
        self.assertIn("GATES FAILED", page)
        self.assertRegex(page, rf'<tr class="FAIL" id="gate-{re.escape(gid)}"')
        self.assert_one_line_messages(proc.stderr)

    def test_non_finite_measurement_fails(self):
        gid = "fixture.constants.lattice_sum_m8"
        self.edit_json(self.gate_path(gid), measured="non-finite", verdict="FAIL")
        proc, page = self.run_report()
        self.assertEqual(proc.returncode, 1)
        self.assertIn("non-finite", page)
        self.assertRegex(page, rf'<tr class="FAIL" id="gate-{re.escape(gid)}"')


class MalformedInputs(ReportTestCase):
    def check_malformed(self, path, words):
        proc, page = self.run_report()
        self.assertEqual(proc.returncode, 1)
        lines = [l for l in proc.stderr.splitlines() if str(path) in l]
        self.assertEqual(len(lines), 1, proc.stderr)
        self.assertIn("MALFORMED", lines[0])
        for word in words:
            self.assertIn(word, lines[0])
        self.assertIn("MALFORMED", page)
        self.assert_one_line_messages(proc.stderr)
        self.assert_self_contained(page)
        return page

    def test_truncated_gate_json(self):
        path = self.gate_path("fixture.bar.energy_drift")
        path.write_text(path.read_text()[:60])
        page = self.check_malformed(path, ["invalid JSON", "line"])
        self.assertRegex(page, r'<tr class="MALFORMED" id="gate-fixture.bar.energy_drift"')
        self.assertIn("3 passed", page)   # the others are still there

    def test_unreadable_gate_still_shows_in_the_problem_that_lists_it(self):
        path = self.gate_path("fixture.constants.lattice_sum_m8")   # listed in fixture_constants.toml
        path.write_text("{")
        page = self.check_malformed(path, ["invalid JSON"])
        section = page[page.index('id="p-fixture_constants"'):page.index('id="p-fixture_bar"')]
        row = re.search(r'<tr class="MALFORMED"[^>]*>\s*<td class="id">([^<]*(?:<wbr>[^<]*)*)', section)
        self.assertIsNotNone(row, "no MALFORMED row in the problem's own gate table")
        self.assertEqual(row.group(1).replace("<wbr>", ""), "fixture.constants.lattice_sum_m8")

    def test_empty_and_non_object_and_binary_gate_files(self):
        cases = [("", "empty file"), ("[1, 2]", "JSON object"), (b"\xff\xfe\x00", "UTF-8")]
        for content, words in cases:
            with self.subTest(content=content):
                path = self.gate_path("fixture.bar.energy_drift")
                path.write_bytes(content if isinstance(content, bytes) else content.encode())
                self.check_malformed(path, [words])

    def test_gate_with_wrong_fields(self):
        cases = [({"measured": "abc"}, '"measured"'),
                 ({"compare": "roughly"}, '"compare"'),
                 ({"verdict": "FAIL"}, "disagrees"),           # its numbers say PASS
                 ({"tolerance_reason": ""}, "tolerance_reason"),
                 ({"id": "another.id"}, "file is named")]
        original = self.gate_path("fixture.bar.energy_drift").read_text()
        for change, words in cases:
            with self.subTest(change=change):
                path = self.gate_path("fixture.bar.energy_drift")
                path.write_text(original)
                self.edit_json(path, **change)
                self.check_malformed(path, [words])

    def test_malformed_plot_keeps_the_rest_of_the_section(self):
        path = self.results / "data" / "fixture_bar" / "01_displacement.json"
        obj = json.loads(path.read_text())
        obj["series"][0]["y"] = obj["series"][0]["y"][:-3]
        path.write_text(json.dumps(obj))
        page = self.check_malformed(path, ['"x" has 81 values but "y" has 78'])
        self.assertIn("Displacement field snapshot", page)   # the next item still renders
        self.assertIn("INCOMPLETE", page)            # no gate failed, but not everything is there

    def test_error_bars_must_match_the_points(self):
        path = self.results / "data" / "fixture_bar" / "04_bars.json"
        path.write_text(json.dumps({"kind": "plot", "title": "Rates",
                                    "series": [{"x": [1, 2], "y": [3, 4], "ylo": [2], "yhi": [4, 5]}]}))
        self.check_malformed(path, ['"ylo" in series 0 must be a list as long as "y"'])

    def test_unknown_evidence_kind(self):
        path = self.results / "data" / "fixture_bar" / "04_movie.json"
        path.write_text(json.dumps({"kind": "movie", "title": "t"}))
        self.check_malformed(path, ['unknown "kind"'])

    def test_network_reference_in_text_is_refused(self):
        path = self.results / "data" / "fixture_bar" / "03_notes.json"
        path.write_text(json.dumps({"kind": "text", "title": "Notes",
                                    "html": '<p><img src="https://example.org/x.png"></p>'}))
        page = self.check_malformed(path, ["network resource"])
        self.assertNotIn("example.org", page.split('id="issues"')[0])

    def test_malformed_problem_toml(self):
        path = self.problems / "fixture_bar.toml"
        path.write_text(path.read_text() + "\nparamters = []\n")
        page = self.check_malformed(path, ["unknown key", "paramters"])
        self.assertIn("Tip displacement of the vibrating bar", page)  # its results still shown
        path.write_text('id = "fixture_bar"\ntitle = "unterminated\n')
        self.check_malformed(path, ["invalid TOML"])

    def test_recorded_by_naming_a_gate_the_problem_does_not_list(self):
        path = self.problems / "fixture_constants.toml"
        path.write_text(path.read_text() + '\n[recorded_by]\n"fixture.nowhere" = "the full tier"\n')
        self.check_malformed(path, ['"recorded_by" names gate(s) not in "gates"', "fixture.nowhere"])

    def test_malformed_provenance(self):
        path = self.results / "provenance.json"
        self.edit_json(path, threads="two")
        page = self.check_malformed(path, ['"threads"'])
        self.assertIn("provenance", page)

    def test_malformed_instruction_set(self):
        path = self.results / "provenance.json"
        self.edit_json(path, simd=512)
        self.check_malformed(path, ['"simd"'])

    def test_malformed_benchmark_file(self):
        path = self.results / "bench" / "fixture_bench.json"
        path.write_text(json.dumps({"context": {}, "benchmarks": {"not": "a list"}}))
        self.check_malformed(path, ['"benchmarks"'])


class MissingInputs(ReportTestCase):
    def test_no_results_directory(self):
        proc, page = self.run_report(results=self.tmp / "nowhere")
        self.assertEqual(proc.returncode, 1)
        self.assertIn("does not exist", proc.stderr)
        self.assertIn("NO RESULTS", page)
        self.assertIn("does not exist", page)
        self.assert_self_contained(page)

    def test_problem_with_description_but_no_results(self):
        (self.problems / "spare.toml").write_text('id = "spare"\ntitle = "A problem nobody ran"\n')
        proc, page = self.run_report()
        self.assertEqual(proc.returncode, 1)
        self.assertRegex(proc.stderr, r"MISSING: .*spare\.toml")
        section = page[page.index('id="p-spare"'):]
        self.assertIn('class="badge MISSING"', section[:600])
        proc, _ = self.run_report("--allow-missing")
        self.assertEqual(proc.returncode, 0, proc.stderr)

    def test_gate_listed_in_description_but_never_recorded(self):
        self.gate_path("fixture.constants.lattice_sum_m8").unlink()
        proc, page = self.run_report()
        self.assertEqual(proc.returncode, 1)
        self.assertIn("1 missing", proc.stdout)
        self.assertRegex(page, r'<tr class="MISSING" id="gate-fixture.constants.lattice_sum_m8"')

    def test_gate_another_command_records_is_skipped_not_missing(self):
        # The full tier and ci/bench.sh record gates that a CI report does not have.
        path = self.problems / "fixture_constants.toml"
        path.write_text(path.read_text() + '\n[recorded_by]\n"fixture.constants.lattice_sum_m8" = "the full tier"\n')
        self.gate_path("fixture.constants.lattice_sum_m8").unlink()
        proc, page = self.run_report()
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertIn("0 missing", proc.stdout)
        self.assertIn("1 recorded by another command", proc.stdout)
        self.assertRegex(page, r'<tr class="SKIPPED" id="gate-fixture.constants.lattice_sum_m8"')
        self.assertIn("recorded by the full tier", page)
        self.assertIn("ALL GATES PASS", page)

    def test_missing_image_and_provenance(self):
        (self.results / "data" / "fixture_bar" / "snapshot.png").unlink()
        (self.results / "provenance.json").unlink()
        proc, page = self.run_report()
        self.assertEqual(proc.returncode, 1)
        self.assertIn("snapshot.png not found", proc.stderr)
        self.assertIn("provenance.json", proc.stderr)
        self.assertIn("is missing", page)
        self.assertIn('figure class="evidence MISSING"', page)

    def test_results_without_description_get_a_section(self):
        (self.problems / "fixture_bar.toml").unlink()
        proc, page = self.run_report()
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertIn('id="p-fixture_bar"', page)
        self.assertIn("no description", page)


class Citations(ReportTestCase):
    def test_sources_link_to_the_full_entry_and_the_page_lists_what_it_cites(self):
        proc, page = self.run_report()
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertIn('<a class="cite" href="#ref-deryugin2023"', page)
        self.assertIn('<li id="ref-deryugin2023">', page)
        self.assertIn("Investigation of various influence functions in peridynamics.", page)  # full entry beside the gate
        self.assertNotIn("ref-unused1999", page, "only cited works are listed")

    def test_a_source_without_a_key_is_malformed(self):
        self.edit_json(self.gate_path("fixture.bar.energy_drift"), source="Hairer et al. 2006")
        proc, _ = self.run_report()
        self.assertEqual(proc.returncode, 1)
        self.assertIn("names no bibliography key", proc.stderr)
        self.assert_one_line_messages(proc.stderr)

    def test_an_unknown_key_is_malformed(self):
        self.edit_json(self.gate_path("fixture.bar.energy_drift"), source="[nobody2001] eq 3")
        proc, _ = self.run_report()
        self.assertEqual(proc.returncode, 1)
        self.assertIn("cites [nobody2001], which references.md does not list", proc.stderr)

    def test_no_bibliography_is_missing_not_a_crash(self):
        proc, page = self.run_report("--references", str(self.tmp / "none.md"), "--allow-missing")
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertIn("no bibliography", proc.stderr)
        self.assertIn("[deryugin2023] table 4.2", page)


class CommandLine(ReportTestCase):
    def test_usage_errors_give_status_2(self):
        proc = subprocess.run([sys.executable, str(SCRIPT), "--no-such-option"], capture_output=True, text=True)
        self.assertEqual(proc.returncode, 2)
        self.assertIn("usage", proc.stderr)
        self.out.mkdir(parents=True)
        proc, _ = self.run_report()
        self.assertEqual(proc.returncode, 2)
        self.assertIn("is a directory", proc.stderr)

    def test_unwritable_output_is_a_clear_error(self):
        blocker = self.tmp / "file"
        blocker.write_text("x")
        args = [sys.executable, str(SCRIPT), "--results", str(self.results), "--problems", str(self.problems),
                "--out", str(blocker / "index.html")]
        proc = subprocess.run(args, capture_output=True, text=True)
        self.assertEqual(proc.returncode, 1)
        self.assertIn("cannot write", proc.stderr)
        self.assertNotIn("Traceback", proc.stderr)


class AtomicWrite(ReportTestCase):
    def test_no_temporary_files_are_left(self):
        self.out.parent.mkdir(parents=True)
        self.out.write_text("old page")
        self.run_report()
        self.assertEqual(sorted(p.name for p in self.out.parent.iterdir()), ["index.html"])
        self.assertTrue(self.out.read_text().rstrip().endswith("</html>"))

    def test_a_failed_write_leaves_the_old_page(self):
        self.out.parent.mkdir(parents=True)
        self.out.write_text("old page")
        with mock.patch("os.replace", side_effect=OSError("disk full")):
            with self.assertRaises(OSError):
                render.write_atomic(self.out, "<html>new</html>")
        self.assertEqual(self.out.read_text(), "old page")
        self.assertEqual(sorted(p.name for p in self.out.parent.iterdir()), ["index.html"])

    def test_page_appears_only_by_rename(self):
        seen = []
        real_replace = os.replace

        def spy(src, dst):
            seen.append((Path(src).parent, Path(dst), Path(dst).exists()))
            return real_replace(src, dst)

        with mock.patch("os.replace", side_effect=spy):
            render.write_atomic(self.out, "<html>new</html>")
        self.assertEqual(seen, [(self.out.parent, self.out, False)])
        self.assertEqual(self.out.read_text(), "<html>new</html>")


CHROMIUM = Path("/usr/bin/chromium")


@unittest.skipUnless(CHROMIUM.exists(), "needs Debian's chromium to run the page's inline script")
class SortingInBrowser(ReportTestCase):
    def test_clicking_a_column_head_sorts_numerically(self):
        self.run_report()
        probe = self.tmp / "probe.html"
        probe.write_text(self.out.read_text() + """<script>
var table = document.querySelector("table.gates");
var head = table.tHead.rows[0].cells[2];   // Measured
function column() { return Array.from(table.tBodies[0].rows).map(r => r.cells[2].getAttribute("data-sort")).join(","); }
head.click(); var up = column(); head.click(); var down = column();
document.body.setAttribute("data-probe", up + "|" + down);
</script>""")
        profile = self.tmp / "profile"
        proc = subprocess.run(
            [str(CHROMIUM), "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
             "--disable-background-networking", "--disable-component-update", "--disable-sync",
             f"--user-data-dir={profile}", "--dump-dom", probe.as_uri()],
            capture_output=True, text=True, timeout=120)
        found = re.search(r'data-probe="([^"]*)"', proc.stdout)
        self.assertIsNotNone(found, "the inline script did not run")
        up, down = found.group(1).split("|")
        values = [float(v) for v in up.split(",")]
        self.assertEqual(values, sorted(values))
        self.assertEqual(down.split(","), up.split(",")[::-1])


class NumberFormatting(unittest.TestCase):
    def test_significant_digits_and_scientific_notation(self):
        cases = {0.0336: "0.0336", 3.015: "3.015", 1 / 3: "0.3333", 200e9: "2×10<sup>11</sup>",
                 -2.5e-7: "−2.5×10<sup>−7</sup>", 1e-5: "10<sup>−5</sup>", 531414: "531414",
                 None: "—", float("nan"): "NaN", "a<b": "a&lt;b", True: "true"}
        for value, text in cases.items():
            with self.subTest(value=value):
                self.assertEqual(str(numfmt.num(value)), text)
        self.assertEqual(str(numfmt.num(1 / 3, 7)), "0.3333333")
        self.assertEqual(str(numfmt.rate(1.95e9, "B/s")), "1.95 GB/s")


if __name__ == "__main__":
    unittest.main()
