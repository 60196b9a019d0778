// Interrupts that keep the work (Ctrl-C, SIGTERM): the first signal asks the render loop to
// stop after the pass in flight, so the image of the samples done so far is written and
// the program exits 130 (SIGINT) or 143 (SIGTERM); a second signal exits at once, removing
// an image that was being written so no half-written file is left.
// Not part of the article: the machinery of the stage programs.
#pragma once

namespace pt {

// Installs the handlers (the stage programs do; tests do not).
void install_interrupt_handlers();

// The signal that asked the render to stop, or 0.
int interrupt_signal();

// The temporary file being written now ("" when none): a second signal removes it.
void set_file_in_progress(const char* path);

}  // namespace pt
