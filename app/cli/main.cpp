#include <cstdio>

int main() {
    std::puts("radiosity-cli: under construction");
    return 0;
}
