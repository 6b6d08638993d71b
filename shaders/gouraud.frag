#version 450
// Writes linear radiosity; tone mapping happens where the image is encoded.
layout(location = 0) in vec3 inColor;
layout(location = 0) out vec4 outColor;

void main() {
    outColor = vec4(inColor, 1.0);
}
