"""The parts of tools/test_grade_lab.py, the test of tools/grade_lab.py (grading a class's lab
submissions; tooling for teachers, not a part of the article):
  support.py   the checks' one way to pass or fail (expect), the paths, and writing submissions;
  fixtures.py  lab 2's and lab 4's fixture submissions, the attacks of issue 47 among them;
  graded.py    labs 2 and 4 graded on them and every verdict checked (the default, slow part);
  fast.py      the quick part (--fast): source check, sandbox, report, hint tables, CSV, rebuilds."""
