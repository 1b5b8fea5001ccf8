// The public face of the renderer: each call is RendererCore's.

#include "encore/render/Renderer.h"

#include "render/renderer/RendererCore.h"

namespace encore::render {

RendererCore& internals(Renderer& renderer) {
    return *renderer.mCore;
}

const RendererCore& internals(const Renderer& renderer) {
    return *renderer.mCore;
}

Result<Renderer> Renderer::create(gpu::Context& context, const RendererOptions& options) {
    Result<RendererCore> core = RendererCore::create(context, options);
    if (!core) {
        return core.error();
    }
    Renderer renderer;
    renderer.mCore = std::make_unique<RendererCore>(std::move(*core));
    return renderer;
}

Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;
Renderer::~Renderer() = default;

Result<void> Renderer::createKeptObjects(StrategyKind kind) {
    return mCore->createKeptObjects(kind);
}

Result<void> Renderer::prepare(const scene::SceneData& scene, StrategyKind kind, bool bundle) {
    return mCore->prepare(scene, kind, bundle);
}

Result<void> Renderer::setStrategy(StrategyKind kind, bool bundle) {
    return mCore->setStrategy(kind, bundle);
}

void Renderer::releaseScene() {
    mCore->releaseScene();
}

bool Renderer::bundled() const {
    return mCore->bundled();
}

const scene::SceneData* Renderer::scene() const {
    return mCore->scene();
}

void Renderer::setCullingCamera(std::optional<Camera> camera) {
    mCore->setCullingCamera(camera);
}

const std::optional<Camera>& Renderer::cullingCamera() const {
    return mCore->cullingCamera();
}

void Renderer::setCullingOptions(const CullingOptions& culling) {
    mCore->setCullingOptions(culling);
}

const CullingOptions& Renderer::cullingOptions() const {
    return mCore->cullingOptions();
}

FrameResult Renderer::renderFrame(const Camera& camera, float timeSeconds) {
    return mCore->renderFrame(camera, timeSeconds);
}

FrameResult Renderer::renderViews(std::span<const Camera> cameras, float timeSeconds) {
    return mCore->renderViews(cameras, timeSeconds);
}

Result<void> Renderer::resize(std::uint32_t width, std::uint32_t height) {
    return mCore->resize(width, height);
}

Result<void> Renderer::updateInstance(std::size_t instance, const glm::mat4& world) {
    return mCore->updateInstance(instance, world);
}

Result<void> Renderer::setAnimationEvaluation(AnimationEvaluation evaluation) {
    return mCore->setAnimationEvaluation(evaluation);
}

AnimationEvaluation Renderer::animationEvaluation() const {
    return mCore->animationEvaluation();
}

Result<void> Renderer::selectAnimation(std::string_view nameOrIndex) {
    return mCore->selectAnimation(nameOrIndex);
}

Result<void> Renderer::setAnimationTime(double seconds) {
    return mCore->setAnimationTime(seconds);
}

void Renderer::setPlaybackMode(scene::PlaybackMode mode) {
    mCore->setPlaybackMode(mode);
}

scene::PlaybackMode Renderer::playbackMode() const {
    return mCore->playbackMode();
}

const AnimationFrameStats& Renderer::animationStats() const {
    return mCore->animationStats();
}

const scene::AnimationPlayer* Renderer::animationPlayer() const {
    return mCore->animationPlayer();
}

Result<void> Renderer::updateMaterial(scene::MaterialId material, const scene::Material& value) {
    return mCore->updateMaterial(material, value);
}

Result<void> Renderer::replaceBaseColorImage(scene::MaterialId material,
                                             const scene::Image& image) {
    return mCore->replaceBaseColorImage(material, image);
}

Result<void> Renderer::selectVariant(std::optional<scene::VariantId> variant) {
    return mCore->selectVariant(variant);
}

std::optional<scene::VariantId> Renderer::variant() const {
    return mCore->variant();
}

void Renderer::setLighting(const LightingParameters& parameters) {
    mCore->setLighting(parameters);
}

const LightingParameters& Renderer::lighting() const {
    return mCore->lighting().parameters();
}

Result<void> Renderer::setToneMapping(const ToneMappingOptions& options) {
    return mCore->setToneMapping(options);
}

const ToneMappingOptions& Renderer::toneMapping() const {
    return mCore->toneMapping();
}

Result<void> Renderer::loadEnvironment(const image::HdrImage& panorama) {
    return mCore->loadEnvironment(panorama);
}

std::shared_ptr<Environment> Renderer::environment() const {
    return mCore->environment();
}

void Renderer::setEnvironment(std::shared_ptr<Environment> environment) {
    mCore->setEnvironment(std::move(environment));
}

Result<void> Renderer::updateLight(std::size_t lightInstance,
                                   const scene::Light& light,
                                   const scene::LightInstance& placed) {
    return mCore->updateLight(lightInstance, light, placed);
}

void Renderer::toneMapScene() {
    mCore->toneMapScene();
}

void Renderer::setTriangleCounting(bool on) {
    mCore->setTriangleCounting(on);
}

bool Renderer::triangleCounting() const {
    return mCore->triangleCounting();
}

Result<std::vector<DrawnTriangles>> Renderer::takeTriangleHistory() {
    return mCore->takeTriangleHistory();
}

Result<std::vector<std::uint64_t>> Renderer::takeDrawnTriangles() {
    return mCore->takeDrawnTriangles();
}

Result<image::ImageRgba8> Renderer::readImage() {
    return mCore->readImage();
}

Result<std::vector<float>> Renderer::readHdrImage() {
    return mCore->readHdrImage();
}

wgpu::Texture Renderer::passTexture(PassImage image) const {
    return mCore->passTexture(image);
}

wgpu::TextureView Renderer::passBytesView(PassImage image) const {
    return mCore->passBytesView(image);
}

Result<void> Renderer::recoverFromDeviceLoss() {
    return mCore->recoverFromDeviceLoss();
}

const RenderTarget& Renderer::target() const {
    return mCore->target();
}

RendererStats Renderer::stats() const {
    return mCore->stats();
}

gpu::Context& Renderer::context() {
    return mCore->context();
}

}  // namespace encore::render
