// Real-browser test of the EXT_normal_mesh_compression three.js plugin: headless
// Chromium (playwright-core, the system's /usr/bin/chromium) opens the demo page
// samples/web/ from a localhost server and must show every level with the vertex
// and triangle counts of the native C++ decoder, stream a split .gltf level by
// level with Range requests, and turn a corrupt stream into an error message
// rather than a hang; a textured asset must render like its original from the same
// camera. scripts/test-web.sh prepares the inputs in EQMESH_WEB_WORK:
// models/NAME.glb, models/split/NAME.gltf, corrupt.glb, native.json
// ({ NAME: { "levels": J, "counts": [{ "vertices": V, "triangles": T }, ...] } }) and,
// with the shared meshes, models/duck_original.glb and its compressed models/duck.glb.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startStaticServer } from './static_server.mjs';

const ROOT = path.resolve( path.dirname( fileURLToPath( import.meta.url ) ), '../..' );
const WORK = path.resolve( process.env.EQMESH_WEB_WORK || path.join( ROOT, 'build-test/web' ) );
const MODEL = 'blob'; // the corrupt copy and the file-picker test use this one
const SCREENSHOT = process.env.EQMESH_WEB_SCREENSHOT || path.join( WORK, 'screenshot.png' );
const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';
// Generous for 2 shared cores and software WebGL; a hang still ends the test.
const WAIT_MS = 60000;
const native = JSON.parse( fs.readFileSync( path.join( WORK, 'native.json' ), 'utf8' ) );

let browser;
let server;

before( async () => {

	assert.ok( WORK.startsWith( ROOT + path.sep ), `${WORK} must lie inside the served root ${ROOT}` );
	server = await startStaticServer( ROOT );
	browser = await chromium.launch( {
		executablePath: CHROMIUM,
		headless: true,
		// SwiftShader draws WebGL without a GPU; background networking stays off so
		// the browser talks to nothing but the local server.
		args: [ '--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking',
			'--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--disable-component-update' ],
	} );

} );

after( async () => {

	if ( browser ) await browser.close();
	if ( server ) await new Promise( ( resolve ) => server.server.close( resolve ) );

} );

function servedPath( file ) {

	return '/' + path.relative( ROOT, file ).split( path.sep ).join( '/' );

}

// Opens the demo on `model` and waits until it is ready or shows an error.
async function openDemo( model, extra = '' ) {

	const page = await browser.newPage( { viewport: { width: 960, height: 720 } } );
	const problems = [];
	page.on( 'pageerror', ( e ) => problems.push( String( e ) ) );
	// SwiftShader's driver chatter is not the page's problem.
	page.on( 'console', ( m ) => m.type() === 'error' && ! m.text().startsWith( '[.WebGL-' ) && problems.push( m.text() ) );
	page.problems = problems;
	await page.goto( `${server.url}/samples/web/?model=${encodeURIComponent( model )}${extra}` );
	await waitForState( page );
	return page;

}

async function waitForState( page ) {

	await page.waitForFunction( () => [ 'ready', 'error' ].includes( document.body.dataset.state ), null, { timeout: WAIT_MS } );
	return page.evaluate( () => document.body.dataset.state );

}

async function state( page ) {

	return page.evaluate( () => ( {
		state: document.body.dataset.state,
		error: document.getElementById( 'error' ).textContent,
	} ) );

}

function assertCounts( name, shown, level ) {

	const expected = native[ name ].counts[ level ];
	assert.equal( shown.vertices, expected.vertices, `level ${level} vertices` );
	assert.equal( shown.triangles, expected.triangles, `level ${level} triangles` );

}

for ( const name of Object.keys( native ) ) {

	test( `every level of ${name}.glb matches the native decoder`, async () => {

		const page = await openDemo( servedPath( path.join( WORK, 'models', name + '.glb' ) ) );
		const s = await state( page );
		assert.equal( s.state, 'ready', `page state ${s.state}: ${s.error} ${page.problems.join( '; ' )}` );
		const levels = await page.evaluate( () => window.eqmeshDemo.current.plugin.levelsOf( window.eqmeshDemo.current.meshes[ 0 ] ) );
		assert.equal( levels, native[ name ].levels );
		for ( let level = 0; level <= levels; level ++ ) {

			const [ info ] = await page.evaluate( ( k ) => window.eqmeshDemo.setLevel( k ), level );
			assertCounts( name, info, level );

		}
		if ( name === MODEL ) await screenshot( page );
		assert.deepEqual( page.problems, [] );
		await page.close();

	} );

	test( `${name}.gltf arrives coarse to fine through Range requests`, async () => {

		const gltf = servedPath( path.join( WORK, 'models', 'split', name + '.gltf' ) );
		const bin = gltf.replace( /\.gltf$/, '.bin' );
		const page = await openDemo( gltf, '&progressive=1' );
		assert.equal( ( await state( page ) ).state, 'ready' );
		const J = native[ name ].levels;
		await page.waitForFunction( ( last ) => {

			const log = window.eqmeshDemo.current.levelLog;
			return log.length && log[ log.length - 1 ].level === last;

		}, J, { timeout: WAIT_MS } );
		const log = await page.evaluate( () => window.eqmeshDemo.current.levelLog );
		assert.deepEqual( log.map( ( e ) => e.level ), [ ...Array( J + 1 ).keys() ] );
		log.forEach( ( e ) => assertCounts( name, e, e.level ) );
		const binRequests = server.log.filter( ( r ) => r.path === bin );
		assert.ok( binRequests.length >= 2, 'one request per level with new bytes' );
		assert.ok( binRequests.every( ( r ) => r.status === 206 ), JSON.stringify( binRequests ) );
		assert.deepEqual( page.problems, [] );
		await page.close();

	} );

}

async function screenshot( page ) {

	await page.waitForTimeout( 500 ); // a few frames at the finest level
	fs.mkdirSync( path.dirname( SCREENSHOT ), { recursive: true } );
	await page.screenshot( { path: SCREENSHOT } );

}

test( 'a corrupt stream shows an error naming the primitive', async () => {

	const page = await openDemo( servedPath( path.join( WORK, 'corrupt.glb' ) ) );
	const s = await state( page );
	assert.equal( s.state, 'error' );
	assert.match( s.error, /mesh 0 primitive 0: CORRUPT_STREAM: / );
	await page.close();

} );

test( 'a stream cut short shows its complete levels, then an error', async () => {

	const page = await openDemo( servedPath( path.join( WORK, 'models', 'split', MODEL + '_cut.gltf' ) ), '&progressive=1' );
	await page.waitForFunction( () => document.body.dataset.state === 'error', null, { timeout: WAIT_MS } );
	const s = await state( page );
	assert.match( s.error, /mesh 0 primitive 0: IO_ERROR: .*short range response/ );
	const log = await page.evaluate( () => window.eqmeshDemo.current.levelLog );
	assert.deepEqual( log.map( ( e ) => e.level ), [ 0, 1, 2 ] );
	const drawn = await page.evaluate( () => window.eqmeshDemo.current.meshes[ 0 ].geometry.drawRange.count );
	assert.equal( drawn, 0, 'the failed primitive is not drawn' );
	await page.close();

} );

test( 'a .glb picked by the user loads', async () => {

	const page = await openDemo( servedPath( path.join( WORK, 'corrupt.glb' ) ) );
	await page.setInputFiles( '#file', path.join( WORK, 'models', MODEL + '.glb' ) );
	await page.waitForFunction( () => document.body.dataset.state === 'ready', null, { timeout: WAIT_MS } );
	const info = await page.evaluate( () => window.eqmeshDemo.current.info );
	assertCounts( MODEL, info, native[ MODEL ].levels );
	await page.close();

} );

// Image PSNR of two screenshots over the pixels where either shows the object (the
// background colour, #2a2f37, is left out: it would flatter the score).
async function screenshotPsnr( page, a, b ) {

	return page.evaluate( async ( [ a64, b64 ] ) => {

		const pixels = async ( b64png ) => {

			const image = await createImageBitmap( await ( await fetch( 'data:image/png;base64,' + b64png ) ).blob() );
			const canvas = new OffscreenCanvas( image.width, image.height );
			const context = canvas.getContext( '2d' );
			context.drawImage( image, 0, 0 );
			return context.getImageData( 0, 0, image.width, image.height ).data;

		};
		const [ pa, pb ] = await Promise.all( [ pixels( a64 ), pixels( b64 ) ] );
		const background = [ 0x2a, 0x2f, 0x37 ];
		const isBackground = ( p, i ) => background.every( ( c, k ) => Math.abs( p[ i + k ] - c ) <= 2 );
		let sum = 0, count = 0;
		for ( let i = 0; i < pa.length; i += 4 ) {

			if ( isBackground( pa, i ) && isBackground( pb, i ) ) continue;
			for ( let k = 0; k < 3; k ++ ) sum += ( pa[ i + k ] - pb[ i + k ] ) ** 2;
			count += 3;

		}
		return { psnr: 10 * Math.log10( 255 * 255 / ( sum / Math.max( count, 1 ) ) ), objectPixels: count / 3 };

	}, [ a.toString( 'base64' ), b.toString( 'base64' ) ] );

}

async function objectShot( model, file ) {

	const page = await openDemo( servedPath( model ) );
	assert.equal( ( await state( page ) ).state, 'ready', ( await state( page ) ).error );
	await page.evaluate( () => document.getElementById( 'panel' ).style.setProperty( 'display', 'none' ) );
	await page.waitForTimeout( 500 ); // a few frames
	const shot = await page.screenshot( { path: file } );
	return { page, shot };

}

test( 'a compressed textured asset renders like its original from the same camera', async ( t ) => {

	const original = path.join( WORK, 'models', 'duck_original.glb' );
	const compressed = path.join( WORK, 'models', 'duck.glb' );
	if ( ! fs.existsSync( original ) || ! fs.existsSync( compressed ) ) {

		t.skip( 'no textured test asset (../shared/meshes/textured/duck.glb)' );
		return;

	}
	const a = await objectShot( original, path.join( WORK, 'screenshot_duck_original.png' ) );
	const b = await objectShot( compressed, path.join( WORK, 'screenshot_duck_decoded.png' ) );
	const hasUv = await b.page.evaluate( () => window.eqmeshDemo.current.meshes[ 0 ].geometry.getAttribute( 'uv' ) !== undefined );
	assert.ok( hasUv, 'the decoded primitive has TEXCOORD_0' );
	const { psnr, objectPixels } = await screenshotPsnr( b.page, a.shot, b.shot );
	console.log( `textured duck: screenshot PSNR ${psnr.toFixed( 2 )} dB over ${objectPixels} object pixels` );
	assert.ok( objectPixels > 10000, 'the duck fills part of the view' );
	assert.ok( psnr >= 30, `screenshot PSNR ${psnr.toFixed( 2 )} dB < 30` );
	assert.deepEqual( [ ...a.page.problems, ...b.page.problems ], [] );
	await a.page.close();
	await b.page.close();

} );
