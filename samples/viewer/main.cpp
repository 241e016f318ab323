// sao-viewer: the interactive parameter-tweak sample. `sao-viewer --help` lists the options.
#include "app.h"

int main(int argc, char** argv) {
  const sao::viewer::Options options = sao::viewer::parseOptions(argc, argv);
  return sao::viewer::runViewer(options);
}
