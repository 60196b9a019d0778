"""The attacks of issue 47 for the grader's test (tools/test_grade_lab.py): C++ that a lab
file hides from GLSL behind #ifdef __cplusplus, to plant files outside its folder, rewrite
the test report, or flood the grader with output. tools/grade_lab.py must refuse or contain
each. Not part of the article: tooling for teachers."""

# C++ that a lab file can hide from GLSL behind #ifdef __cplusplus: the attacks of issue 47.
# The file is included inside the kernel's namespace, so the system calls are declared here
# under names of their own (asm labels), with C linkage.
ATTACK_DECLARATIONS = r"""
#ifdef __cplusplus
extern "C" int grade_attack_open(const char*, int, ...) __asm__("open");
extern "C" long grade_attack_write(int, const void*, unsigned long) __asm__("write");
extern "C" long grade_attack_read(int, void*, unsigned long) __asm__("read");
extern "C" int grade_attack_close(int) __asm__("close");
"""
ATTACK_END = "#endif\n"


def plant_attack(targets, reference, copy_to):
    """C++ that, as the program starts, writes a file at each of targets and copies reference to copy_to."""
    paths = ", ".join(f'"{t}"' for t in targets)
    return ATTACK_DECLARATIONS + f"""struct GradeAttackPlant {{
  GradeAttackPlant() {{
    const char* targets[] = {{{paths}}};
    for (const char* t : targets) {{
      int fd = grade_attack_open(t, 01 | 0100 | 01000, 0644);
      if (fd >= 0) {{ grade_attack_write(fd, "planted\\n", 8); grade_attack_close(fd); }}
    }}
    char buf[1 << 16];
    int in = grade_attack_open("{reference}", 0);
    int out = grade_attack_open("{copy_to}", 01 | 0100 | 01000, 0644);
    long n = in >= 0 ? grade_attack_read(in, buf, sizeof buf) : -1;
    if (n > 0 && out >= 0) grade_attack_write(out, buf, (unsigned long)n);
  }}
}};
static GradeAttackPlant grade_attack_plant;
""" + ATTACK_END


def report_attack(files):
    """C++ that, at exit, writes a passing Catch2 report into each of files and every fd from 1 to 63."""
    paths = ", ".join(f'"{f}"' for f in files)
    fake = ('<?xml version=\\"1.0\\" encoding=\\"UTF-8\\"?>\\n<Catch name=\\"pt_tests\\">\\n'
            '<OverallResults successes=\\"20\\" failures=\\"0\\" expectedFailures=\\"0\\"/>\\n</Catch>\\n')
    return ATTACK_DECLARATIONS + f"""struct GradeAttackReport {{
  ~GradeAttackReport() {{
    static const char fake[] = "{fake}";
    const char* files[] = {{{paths}}};
    for (const char* f : files) {{
      int fd = grade_attack_open(f, 01 | 0100 | 01000, 0644);
      if (fd >= 0) {{ grade_attack_write(fd, fake, sizeof fake - 1); grade_attack_close(fd); }}
    }}
    for (int fd = 1; fd < 64; ++fd) grade_attack_write(fd, fake, sizeof fake - 1);
  }}
}};
static GradeAttackReport grade_attack_report;
""" + ATTACK_END


PRINT_ATTACK = ATTACK_DECLARATIONS + """struct GradeAttackPrint {
  GradeAttackPrint() {
    static char block[1 << 16];
    for (unsigned i = 0; i < sizeof block; ++i) block[i] = 'x';
    for (int k = 0; k < (1 << 14); ++k) grade_attack_write(1, block, sizeof block);  // 1 GiB
  }
};
static GradeAttackPrint grade_attack_print;
""" + ATTACK_END
