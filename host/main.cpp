// Placeholder entry point; replaced by the CLI (host/cli) in the foundation work.
int main() { return 0; }
